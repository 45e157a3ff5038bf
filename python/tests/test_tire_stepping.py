"""flowmbd.tire.Simulation (issue 39 item 6): the tire rolling on the cleat rig, stepped from
Python. Reference: the cleat study (`flowmbd.tire.cleat`), which starts and steps the same
rolling tire through the same library functions: a stepped run reproduces its force history
row by row; a drive torque changes the longitudinal force (a second, independent run)."""

import numpy as np
import pytest

import flowmbd
from tire_case import RIG


def test_stepping_reproduces_the_cleat_history(reduced):
    ref = flowmbd.tire.cleat(60.0, RIG, tire=reduced, series=True)["forces"]
    sim = flowmbd.tire.Simulation({**RIG, "rig": {**RIG["rig"], "speed_kmh": 60.0}}, tire=reduced)
    assert sim.t == 0.0 and sim.settle_time == pytest.approx(0.05)
    rows = []
    sim.run_to(sim.settle_time + 0.05, observer=lambda s: rows.append(s.forces()))
    assert len(rows) == len(ref["t_s"]) == 500
    for col in ("t_s", "fx_N", "fy_N", "f_lateral_N", "spin_rad_per_s", "normal_sum_N", "my_N_m"):
        np.testing.assert_allclose([r[col] for r in rows], ref[col], rtol=1e-12, atol=1e-9,
                                   err_msg=col)
    assert sim.coordinates.ndim == 1 and np.all(np.isfinite(sim.coordinates))
    assert sim.contact_positions.shape == (33, 3)
    assert sim.normal_forces.shape == (33,)


def test_drive_torque_pushes_the_tire_forward(reduced):
    # reference: free rolling (no drive torque) from the same start; a positive drive torque
    # makes the road push the tire forward (F_x grows), Pacejka's sign convention (ISO 8855).
    # The drum without its cleat: with it, the cleat passes the patch one drum revolution
    # before the settle time's end (t = -0.476 s), and step 200 (t = -0.46 s) would compare
    # two values inside that impact's transient (about 50 kN of F_x) instead of the drive.
    rig = {**RIG, "rig": {**RIG["rig"], "settle_time": 0.5, "ground": {"cleat": False}}}
    free = flowmbd.tire.Simulation(rig, tire=reduced)
    driven = flowmbd.tire.Simulation(rig, tire=reduced)
    driven.drive_torque = 500.0
    for s in (free, driven):
        s.step(200)
    assert driven.forces()["fx_N"] > free.forces()["fx_N"] + 100.0
    with pytest.raises(ValueError, match="drive_torque"):
        driven.drive_torque = float("nan")
    with pytest.raises(ValueError, match="speed_kmh"):
        flowmbd.tire.Simulation({"rig": {"speed_kmh": -1.0}}, tire=reduced)


def test_a_saved_state_restarts_the_run(reduced):
    # reference: the run that was never stopped (Rust test tire_restart holds the same through
    # a cleat impact): a restart in a fresh simulation and one in the same simulation step
    # alike, and follow the uninterrupted run to the effect of re-formed matrices
    sim = flowmbd.tire.Simulation(RIG, tire=reduced)
    sim.step(100)
    saved = sim.state()
    load = sim.forces()["fy_N"]  # the carried load, about 4.5 kN
    assert set(saved) == {"t", "z", "zd", "zdd", "acc", "theta", "theta_d", "theta_dd",
                          "theta_acc", "lambda", "friction", "contact_force"}
    assert saved["friction"].shape == (33, 3) and saved["lambda"].shape == (33,)

    def run(s):
        rows = []
        for _ in range(50):
            s.step()
            rows.append([s.forces()[c] for c in ("fx_N", "fy_N", "normal_sum_N")])
        return np.array(rows)

    uninterrupted = run(sim)
    sim.set_state(saved)
    assert sim.t == saved["t"]
    again = run(sim)
    fresh = flowmbd.tire.Simulation(RIG, tire=reduced)
    fresh.set_state({k: (v.tolist() if hasattr(v, "tolist") else v) for k, v in saved.items()})
    other = run(fresh)
    np.testing.assert_allclose(again, other, rtol=0, atol=1e-9 * load)
    np.testing.assert_allclose(again, uninterrupted, rtol=0, atol=1e-3 * load)


def test_a_bad_state_names_the_key(reduced):
    sim = flowmbd.tire.Simulation(RIG, tire=reduced)
    good = sim.state()
    with pytest.raises(ValueError, match="missing key 'acc'"):
        sim.set_state({k: v for k, v in good.items() if k != "acc"})
    with pytest.raises(ValueError, match=r"state\.z: .*values"):
        sim.set_state({**good, "z": good["z"][:-1]})
    with pytest.raises(ValueError, match=r"state\.lambda"):
        sim.set_state({**good, "lambda": np.full_like(good["lambda"], np.nan)})
    with pytest.raises(ValueError, match=r"state\.t: expected a number"):
        sim.set_state({**good, "t": "later"})
    with pytest.raises(ValueError, match="state: expected a dict"):
        sim.set_state([1, 2])
    sim.step(1)


def test_prescribed_spin_holds_the_rate_and_reports_its_torque(reduced):
    # reference: the free-rolling run from the same start (Rust test tire_prescribed checks the
    # reaction torque against a wheel of huge inertia): a spin held 0.3 % above the free
    # rolling one makes the road push the tire forward, held by a positive (driving) reaction
    # torque that is the whole torque on the wheel (no drive torque); freed again, the
    # reaction is gone. The free-rolling spin is that run's settled spin (on the drum it is
    # 0.7 % above the start's `v/R_e` estimate, so 0.3 % above the start would brake);
    # compared are means over the last 50 ms of 0.2 s, past the start's transient. The drum
    # without its cleat (test_drive_torque_pushes_the_tire_forward says why).
    rig = {**RIG, "rig": {**RIG["rig"], "settle_time": 0.5, "ground": {"cleat": False}}}

    def run(s, steps=1000, window=250):
        rows = []
        for _ in range(steps):
            s.step()
            rows.append((s.forces()["fx_N"], s.spin, s.reaction_torque))
        return np.mean(rows[-window:], axis=0)

    free = flowmbd.tire.Simulation(rig, tire=reduced)
    fx_free, spin_free, _ = run(free)
    sim = flowmbd.tire.Simulation(rig, tire=reduced)
    assert sim.prescribed_spin is None and sim.reaction_torque == 0.0
    omega = spin_free * 1.003
    sim.prescribe_spin(omega)
    fx, _, reaction = run(sim)
    assert sim.prescribed_spin == omega
    assert sim.spin == pytest.approx(omega, rel=1e-12)
    assert fx > fx_free + 100.0, f"F_x {fx_free} -> {fx}"
    assert reaction > 10.0
    assert sim.spin_torque == sim.reaction_torque
    sim.drive_torque = 50.0
    sim.step()
    assert sim.spin_torque == pytest.approx(sim.reaction_torque + 50.0, rel=1e-12)
    sim.prescribe_spin(None)
    sim.step()
    assert sim.prescribed_spin is None and sim.reaction_torque == 0.0
    with pytest.raises(ValueError, match="rate"):
        sim.prescribe_spin(float("nan"))
    with pytest.raises(ValueError, match="rate"):
        sim.prescribe_spin("fast")
