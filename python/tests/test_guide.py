"""The user guide's Python blocks run (issue 39 item 1: every code block of the guide run by a
test; the Rust test `apps/cli/tests/user_guide.rs` runs its shell commands and TOML files).
The ``python`` blocks of each chapter run in order as one script, from a scratch folder (a
block may use what an earlier block of its chapter defined, e.g. ``SMALL``, and files it
writes land there), with the `__main__` guard in force as for a user's script; the script must
exit 0."""

import pathlib
import re
import subprocess
import sys

import pytest

GUIDE = pathlib.Path(__file__).resolve().parents[2] / "docs" / "guide" / "src"
FENCE = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


def chapters():
    return sorted(p for p in GUIDE.glob("*.md") if FENCE.search(p.read_text()))


def test_the_guide_has_python_blocks():
    # the chapter on Python and Dask exists and holds its examples (else the test below runs none)
    assert [p.name for p in chapters()] == ["python.md"]


@pytest.mark.parametrize("chapter", chapters(), ids=lambda p: p.name)
def test_python_blocks_run(chapter, tmp_path):
    blocks = FENCE.findall(chapter.read_text())
    script = tmp_path / f"guide_{chapter.stem}.py"
    script.write_text("\n\n".join(blocks))
    p = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                       text=True, timeout=900)
    assert p.returncode == 0, f"{chapter.name}: exit {p.returncode}\n{p.stderr[-3000:]}"
