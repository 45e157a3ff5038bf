"""The Python studies equal the CLI's summary.json (reference: the `flowmbd-*` binaries, which
call the same library functions through the app layer) to 1e-12 relative."""

import flowmbd
from compare import assert_same


def test_speed_loss_equals_cli(cli):
    code, ref, err = cli("belt", "speed-loss", "--omega", "62.8", "--torques", "0,10")
    assert code == 0, err
    py = flowmbd.belt.speed_loss(omega=62.8, torques=[0.0, 10.0])
    assert_same(py["points"], ref["points"], rtol=0)  # the check: exactly equal
    assert_same(py, ref)


def test_speed_loss_config_dict_equals_cli_config_file(cli, tmp_path):
    # a config dict with the TOML keys gives what the CLI gives for the same TOML file; both are
    # partial (one number of the default drive), read deeply over the defaults (issue 39)
    (tmp_path / "c.toml").write_text(
        "omegas = [22.6]\n[procedure]\ntorques = [5.0]\n[drive]\ntension = 300.0\n"
    )
    code, ref, err = cli("belt", "speed-loss", "--config", str(tmp_path / "c.toml"))
    assert code == 0, err
    py = flowmbd.belt.speed_loss(
        omega=None,
        torques=None,
        config={"omegas": [22.6], "procedure": {"torques": [5.0]}, "drive": {"tension": 300.0}},
    )
    assert_same(py, ref)


def test_string_modes_equals_cli(cli):
    code, ref, err = cli("string", "modes", "--speed", "20", "--nodes", "99", "--modes", "40")
    assert code == 0, err
    py = flowmbd.string.modes(speed=20.0, nodes=99, modes=40)
    assert py["flowing_hz"].dtype == float
    assert_same(py, ref)


def test_ancf_dynamic_equals_cli(cli):
    # Kerkkänen example 3.3-B, shortened to 0.15 s (the driver ramp has started)
    code, ref, err = cli("belt", "ancf", "--t-end", "0.15")
    assert code == 0, err
    py = flowmbd.belt.ancf(t_end=0.15)
    assert_same(py, ref)
    assert py["omega_driver_end"] > 0 and py["steps"] > 0


def test_ancf_closure_equals_cli(cli, tmp_path):
    # Kerkkänen example 3.3-A
    (tmp_path / "c.toml").write_text('analysis = "static_closure"\n')
    code, ref, err = cli("belt", "ancf", "--config", str(tmp_path / "c.toml"))
    assert code == 0, err
    assert_same(flowmbd.belt.ancf(config={"analysis": "static_closure"}), ref)


def test_plate_equals_cli(cli):
    # Kerkkänen §4.6 Model 2, shortened to 5 ms (initial static state and the first steps)
    code, ref, err = cli("belt", "plate", "--t-end", "0.005")
    assert code == 0, err
    py = flowmbd.belt.plate(t_end=0.005)
    assert_same(py, ref)
    assert py["steps"] > 0 and abs(py["analytical_omega_driven"] / 500.0 - 0.848) < 2e-3


def test_fead_equals_cli(cli):
    # the accessory drive at one engine speed (issue 17 item 5; the CLI's --rpm)
    code, ref, err = cli("belt", "fead", "--rpm", "1500")
    assert code == 0, err
    py = flowmbd.belt.fead(rpm=[1500.0])
    assert_same(py, ref)
    assert len(py["points"]) == 1 and py["meaning"] == ref["meaning"]


def test_design_equals_cli(cli):
    # the steady FEAD design (issue 36 item 1: "available to Python"), two engine speeds and a
    # partial config (one number of the default drive) on both sides
    import json

    code, ref, err = cli("belt", "design", "--rpm", "800,3000")
    assert code == 0, err
    py = flowmbd.belt.design(rpm=[800.0, 3000.0])
    assert_same(py, ref)
    assert len(py["points"]) == 2 and py["layout"] == ref["layout"]


def test_fead_bad_input_is_a_value_error():
    import pytest

    with pytest.raises(ValueError, match="speeds_rpm"):
        flowmbd.belt.fead(rpm=[-100.0])


def test_string_sweep_equals_cli(cli, tmp_path):
    # same as `flowmbd-string sweep` summary.json and sweep.csv on a coarse sweep (12 speeds up
    # to 1.2 c, 30 nodes, 10 modes, 3 tracked frequencies); the supercritical speeds exercise the
    # growth check by a second discretisation
    import numpy as np

    toml = "nodes = 30\nmodes = 10\ngalerkin_terms = 10\nsteps = 12\ntracked = 3\n"
    (tmp_path / "c.toml").write_text(toml)
    code, ref, err = cli("string", "sweep", "--config", str(tmp_path / "c.toml"))
    assert code == 0, err
    config = {"nodes": 30, "modes": 10, "galerkin_terms": 10, "steps": 12, "tracked": 3}
    py = flowmbd.string.sweep(config, series=True)
    series = py.pop("sweep")
    assert_same(py, ref)
    csv = np.genfromtxt(tmp_path / "string" / "sweep.csv", delimiter=",", names=True)
    assert list(series) == list(csv.dtype.names)
    for k in series:
        np.testing.assert_allclose(series[k], csv[k], rtol=1e-9, atol=1e-300, equal_nan=True,
                                   err_msg=k)
    # the exact frequencies vanish near the critical speed and the first is n c/(2L) at rest
    assert abs(series["exact_f1_Hz"][0] / (py["critical_speed"] / 2.0) - 1.0) < 1e-14
    assert len(series["speed_m_per_s"]) == 12


def test_string_sweep_bad_input_names_the_field(cli, tmp_path):
    import pytest

    (tmp_path / "c.toml").write_text("max_speed_ratio = 0.5\n")
    code, _, err = cli("string", "sweep", "--config", str(tmp_path / "c.toml"))
    assert code == 2
    with pytest.raises(ValueError) as e:
        flowmbd.string.sweep({"max_speed_ratio": 0.5})
    assert str(e.value).startswith("max_speed_ratio: must exceed 1")
    assert str(e.value) in err
    with pytest.raises(ValueError, match=r'config\["string"\]\["tension"\]'):
        flowmbd.string.sweep({"string": {"tension": "high"}})


def test_string_simulate_equals_cli(cli, tmp_path):
    # same as `flowmbd-string simulate` summary.json, modal_history.csv and spectra.csv on a short
    # coarse run (30 nodes, 6 modes, 0.2 s)
    import numpy as np

    toml = "nodes = 30\nmodes = 6\nduration = 0.2\n"
    (tmp_path / "c.toml").write_text(toml)
    code, ref, err = cli("string", "simulate", "--speed", "10", "--config",
                         str(tmp_path / "c.toml"))
    assert code == 0, err
    py = flowmbd.string.simulate({"nodes": 30, "modes": 6, "duration": 0.2}, speed=10.0,
                                 series=True)
    series = {k: py.pop(k) for k in ("modal_history", "spectra")}
    assert_same(py, ref)
    for name, cols in series.items():
        csv = np.genfromtxt(tmp_path / "string" / f"{name}.csv", delimiter=",", names=True)
        assert list(cols) == list(csv.dtype.names), name
        for k in cols:
            np.testing.assert_allclose(cols[k], csv[k], rtol=1e-9, atol=1e-300,
                                       err_msg=f"{name}:{k}")
    # RK4 nearly conserves the invariant; the pluck starts from rest at t = 0
    assert abs(py["hamiltonian_drift"]) < 1e-6
    assert series["modal_history"]["t_s"][0] == 0.0 and py["speed"] == 10.0


def test_string_simulate_bad_input_names_the_field(cli, tmp_path):
    import pytest

    code, _, err = cli("string", "simulate", "--speed", "100")
    assert code == 2
    with pytest.raises(ValueError) as e:
        flowmbd.string.simulate(speed=100.0)
    assert str(e.value).startswith("speed: |speed| = 100 m/s is at or above the critical speed")
    assert str(e.value) in err
    with pytest.raises(ValueError, match=r'config\["pluck"\]\["y"\]'):
        flowmbd.string.simulate({"pluck": {"y": 0.1}})


def test_belt_wave_equals_cli(cli, tmp_path):
    # same as `flowmbd-belt wave` summary.json and wave.csv on a short coarse run (10 elements
    # per span, 20 ms at 0.1 ms steps)
    import numpy as np

    toml = (
        "vtk_frames = 5\n[flowing.mesh]\nspan_element = 0.045\n"
        "[wave]\nt_end = 0.02\nstep = 1e-4\nsamples = 100\n"
    )
    (tmp_path / "c.toml").write_text(toml)
    code, ref, err = cli("belt", "wave", "--speed", "10", "--config", str(tmp_path / "c.toml"))
    assert code == 0, err
    config = {
        "vtk_frames": 5,
        "flowing": {"mesh": {"span_element": 0.045}},
        "wave": {"t_end": 0.02, "step": 1e-4, "samples": 100},
    }
    py = flowmbd.belt.wave(config, speed=10.0, series=True)
    cols = py.pop("wave")
    assert_same(py, ref)
    csv = np.genfromtxt(tmp_path / "belt" / "wave.csv", delimiter=",", names=True)
    assert list(cols) == list(csv.dtype.names)
    for k in cols:
        np.testing.assert_allclose(cols[k], csv[k], rtol=1e-9, atol=1e-300, err_msg=k)
    # the running belt's span vibrates lower than the resting one (travelling string)
    assert py["running"]["belt_speed"] == 10.0 and py["rest"]["belt_speed"] == 0.0


def test_belt_wave_bad_input_names_the_field(cli, tmp_path):
    import pytest

    code, _, err = cli("belt", "wave", "--t-end", "-1")
    assert code == 2
    with pytest.raises(ValueError) as e:
        flowmbd.belt.wave(t_end=-1.0)
    assert str(e.value) in err
    with pytest.raises(ValueError, match=r'config\["wave"\]\["samples"\]'):
        flowmbd.belt.wave({"wave": {"samples": -3}})
