"""Shared fixtures: the CLI binaries the Python results are compared with."""

import json
import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def _bin_dir() -> pathlib.Path:
    return pathlib.Path(os.environ.get("FLOWMBD_BIN_DIR", REPO / "target" / "release"))


@pytest.fixture
def cli(tmp_path):
    """Run ``flowmbd-<app> <args> --json --quiet --out tmp`` and return (exit code, summary or
    None, stderr). Without the binaries the test is skipped, unless FLOWMBD_REQUIRE_CLI=1
    (set by .ci/run, which builds them first)."""

    def run(app, *args):
        exe = _bin_dir() / f"flowmbd-{app}"
        if not exe.exists():
            if os.environ.get("FLOWMBD_REQUIRE_CLI") == "1":
                pytest.fail(f"{exe} not built")
            pytest.skip(f"{exe} not built (cargo build --release -p flowmbd-{app})")
        p = subprocess.run(
            [str(exe), *args, "--json", "--quiet", "--out", str(tmp_path / app)],
            capture_output=True,
            text=True,
        )
        summary = json.loads(p.stdout) if p.returncode == 0 else None
        return p.returncode, summary, p.stderr

    return run


@pytest.fixture(scope="session")
def reduced():
    """The small generated tire of `tire_case.TIRE` reduced once for the session (about 2 s)."""
    import flowmbd
    from tire_case import TIRE

    return flowmbd.tire.reduce(TIRE)
