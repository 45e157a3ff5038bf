"""Recursive comparison of a Python result with the CLI's summary.json."""

import numpy as np

# timings differ from run to run by nature
SKIP = ("wall_time_s", "wall_per_simulated_s", "cpu_per_simulated_s", "seconds")
# written by the CLI's runner around a study's summary (issue 35: whether the run completed
# and the files it wrote), not part of the study's result
RUNNER = {"complete", "status", "outputs"}


def assert_same(py, ref, rtol=1e-12, path="summary"):
    if isinstance(ref, dict):
        assert isinstance(py, dict), path
        if path == "summary":
            ref = {k: v for k, v in ref.items() if k not in RUNNER}
        assert set(py) == set(ref), f"{path}: keys {set(py) ^ set(ref)}"
        for k in ref:
            if k not in SKIP:
                assert_same(py[k], ref[k], rtol, f"{path}.{k}")
    elif isinstance(ref, list) and not all(isinstance(x, (int, float)) or x is None for x in ref):
        assert len(py) == len(ref), path
        for i, (a, b) in enumerate(zip(py, ref)):
            assert_same(a, b, rtol, f"{path}[{i}]")
    elif isinstance(ref, (list, float, np.ndarray)):
        b = np.array([np.nan if x is None else x for x in np.atleast_1d(ref).tolist()], float)
        a = np.atleast_1d(np.asarray(py, dtype=float))
        assert a.shape == b.shape, path
        np.testing.assert_allclose(a, b, rtol=rtol, atol=0, equal_nan=True, err_msg=path)
    else:
        assert py == ref, f"{path}: {py!r} != {ref!r}"
