"""Bad input raises ValueError with the CLI's message (reference: the CLI's one-line error on
stderr, exit code 2); numerical failures raise flowmbd.NumericalError with partial results."""

import json
import pickle
import threading
import time

import numpy as np
import pytest
import scipy.sparse as sp

import flowmbd
from compare import assert_same


def test_bad_speed_same_message_as_cli(cli):
    code, _, err = cli("belt", "speed-loss", "--omega=-1", "--torques", "0")
    assert code == 2
    with pytest.raises(ValueError) as e:
        flowmbd.belt.speed_loss(omega=-1.0, torques=[0.0])
    assert str(e.value) == "omegas[0]: must be finite and > 0 [rad/s]"
    assert str(e.value) in err


def test_bad_nodes_same_message_as_cli(cli):
    code, _, err = cli("string", "modes", "--nodes", "2")
    assert code == 2
    with pytest.raises(ValueError) as e:
        flowmbd.string.modes(nodes=2)
    assert str(e.value) == "nodes: needs at least 3 interior nodes, got 2"
    assert str(e.value) in err


def test_bad_config_key_and_model():
    with pytest.raises(ValueError, match="unknown field `omega`"):
        flowmbd.belt.speed_loss(config={"omega": 3.0})
    with pytest.raises(ValueError, match="model"):
        flowmbd.belt.speed_loss(model="tire")
    with pytest.raises(ValueError, match="config"):
        flowmbd.string.modes(config=[1, 2])
    with pytest.raises(ValueError, match=r"procedure\.torques"):
        flowmbd.belt.speed_loss(torques=[])


def test_bad_matrices():
    k = sp.identity(4, format="csr")
    with pytest.raises(ValueError, match="DOF 7 is out of range"):
        flowmbd.reduce.modes(k, k, count=2, fixed=[7])
    with pytest.raises(ValueError, match="K: expected a 3x3 matrix, got 4x4"):
        flowmbd.reduce.modes(sp.identity(3), k, count=2)
    bad = k.copy().astype(float)
    bad[1, 1] = np.nan
    with pytest.raises(ValueError, match="not finite"):
        flowmbd.reduce.craig_bampton(k, bad, boundary=[0], modes=1)
    with pytest.raises(ValueError, match="listed twice"):
        flowmbd.reduce.craig_bampton(k, k, boundary=[0, 0], modes=1)


def test_numerical_failure_has_the_clis_partial_results(cli, tmp_path):
    # a steady-state tolerance of 1.2e-7 rad/s: the 0 N m point meets it after the 3 s spin-up
    # (window means 8.9e-8 rad/s apart), the 10 N m point cannot within max_hold = 0.1 s (the
    # shortest accepted: two 0.05 s windows; its last means 1.6e-7 apart), so the study fails
    # after one point (gross slip is a result, not a failure, since issue 17); reference: the
    # CLI's failed summary.json (exit code 1)
    (tmp_path / "slip.toml").write_text(
        "omegas = [62.8]\n[procedure]\ntorques = [0.0, 10.0]\nmax_hold = 0.1\nspin_up = 3.0\n"
        "tolerance = 1.2e-7\n"
    )
    code, _, err = cli("belt", "speed-loss", "--config", str(tmp_path / "slip.toml"))
    assert code == 1, err
    ref = json.loads((tmp_path / "belt" / "summary.json").read_text())
    assert ref["status"] == "failed"
    with pytest.raises(flowmbd.NumericalError) as e:
        flowmbd.belt.speed_loss(omega=None, torques=None, config={
            "omegas": [62.8],
            "procedure": {"torques": [0.0, 10.0], "max_hold": 0.1, "spin_up": 3.0,
                          "tolerance": 1.2e-7}})
    assert str(e.value) == ref["error"]
    assert_same(e.value.partial, ref["partial"])
    assert len(e.value.partial["points"]) == 1


def test_numerical_error_carries_partial_results_and_pickles():
    # the native layer hands the partial summary over as JSON text (its CLI summary.json form)
    e = flowmbd.NumericalError("step failed", '{"omega_driver": 62.8, "points": [1.0, 2.0]}')
    assert isinstance(e, RuntimeError)
    np.testing.assert_array_equal(e.partial["points"], [1.0, 2.0])
    back = pickle.loads(pickle.dumps(e))
    assert str(back) == "step failed" and back.partial["omega_driver"] == 62.8


def test_long_run_releases_the_gil():
    # reference: the main thread keeps running while a study runs in another thread; if the
    # native call held the GIL, the loop below would not tick until the study returned
    done = threading.Event()

    def run():
        flowmbd.belt.speed_loss(omega=62.8, torques=[0.0, 2.0])
        done.set()

    ticks = 0
    t = threading.Thread(target=run)
    start = time.perf_counter()
    t.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.002)
    t.join()
    elapsed = time.perf_counter() - start
    assert elapsed > 0.2 and ticks > 0.25 * elapsed / 0.002, (ticks, elapsed)


def test_partial_config_errors_name_the_dict_path():
    # issue 39: a dict config is read deeply over the defaults; a bad value deep inside names
    # its dict path (reference: the key written here)
    with pytest.raises(ValueError, match=r'config\["drive"\]\["tension"\]'):
        flowmbd.belt.speed_loss(omega=None, torques=None, config={"drive": {"tension": "high"}})
    with pytest.raises(ValueError, match=r'config\["procedure"\]'):
        flowmbd.belt.speed_loss(omega=None, torques=None, config={"procedure": {"typo": 1}})


def test_version_is_the_packages():
    from importlib.metadata import version

    assert flowmbd.__version__ == version("flowmbd")
