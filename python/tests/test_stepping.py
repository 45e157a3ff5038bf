"""The stepping API (issue 39 item 6): flowmbd.belt.Simulation builds a drive from a layout,
steps it, reads and sets its state, changes a signal between steps and reports any state.
References: the prescribed driver schedule (Ribaric §6.4's C¹ smooth step), Newton's second law
of the driven pulley in a steady state, the speed-loss study run on the same drive, and
determinism of a restart."""

import math

import numpy as np
import pytest

import flowmbd


def smoothstep(t, t0, t1, y0, y1):
    """Ribaric §6.4's schedule between two knots: y0 + (y1 − y0)(3τ² − 2τ³)."""
    tau = min(max((t - t0) / (t1 - t0), 0.0), 1.0)
    return y0 + (y1 - y0) * tau * tau * (3.0 - 2.0 * tau)


@pytest.mark.parametrize("model", ["flowing", "ancf"])
def test_driver_follows_its_schedule(model):
    sim = flowmbd.belt.Simulation({"model": model})
    assert sim.model == model
    assert sim.t == 0.0 and len(sim.q) == len(sim.v) == len(sim.coordinate_names)
    seen = []
    sim.run_to(0.01, observer=lambda s: seen.append((s.t, s.pulley_speeds[0])), every=10)
    h = sim.step_size
    assert len(seen) == math.ceil(round(0.01 / h) / 10)
    assert sim.t == pytest.approx(0.01, abs=1e-12)
    for t, w in seen:
        # the driver's speed is prescribed: the schedule 0 -> 62.8 rad/s over 0.3 s
        assert w == pytest.approx(smoothstep(t, 0.0, 0.3, 0.0, 62.8), rel=1e-9, abs=1e-9)


def test_steady_state_matches_the_speed_loss_study():
    # the defaults: Table 6-1, driver ramped to 62.8 rad/s, load ramped to 10 N m at 0.3-0.4 s
    sim = flowmbd.belt.Simulation()
    sim.run_to(0.8)
    w = sim.pulley_speeds
    report = sim.report()
    driven = report["pulleys"][1]
    # Newton's second law of the driven pulley in a steady state: contact torque = load
    assert driven["torque_n_m"] == pytest.approx(10.0, rel=5e-3)
    # the speed-loss study on the same drive and model (its steady criterion, its windows)
    study = flowmbd.belt.speed_loss(omega=62.8, torques=[10.0])
    dw_study = study["cases"][0]["points"][0]["delta_omega"]
    assert w[0] - w[1] == pytest.approx(dw_study, rel=0.02)
    # unloading between steps: the speed loss goes back to the unloaded one (creep only)
    sim.set_signal(1, {"kind": "constant", "value": 0.0})
    sim.run_to(1.2)
    w = sim.pulley_speeds
    assert abs(w[0] - w[1]) < 0.05 * dw_study


def test_restart_from_a_saved_state_is_deterministic():
    sim = flowmbd.belt.Simulation({"step": 5e-4})
    sim.run_to(0.05)
    t, q, v = sim.state()
    runs = []
    for _ in range(2):
        sim.set_state(t, q, v)
        sim.step(20)
        runs.append(sim.q)
    assert sim.t == pytest.approx(t + 20 * 5e-4, abs=1e-12)
    np.testing.assert_array_equal(runs[0], runs[1])


def test_bad_input_names_the_field():
    with pytest.raises(ValueError, match=r"^drive\.belt\.ea: must be in"):
        flowmbd.belt.Simulation({"drive": {"belt": {"ea": -1.0}}})
    with pytest.raises(ValueError, match=r"^drive\.tension: must be in"):
        flowmbd.belt.Simulation({"drive": {"tension": -5.0}})
    with pytest.raises(ValueError, match="step"):
        flowmbd.belt.Simulation({"step": 0.0})
    with pytest.raises(ValueError, match="unknown field"):
        flowmbd.belt.Simulation({"stepsize": 1e-4})
    sim = flowmbd.belt.Simulation()
    with pytest.raises(ValueError, match="coordinates"):
        sim.set_state(0.0, np.zeros(3), np.zeros(3))
    with pytest.raises(ValueError, match="n"):
        sim.step(-1)
    with pytest.raises(ValueError, match="pulley"):
        sim.set_signal(7, {"kind": "constant", "value": 1.0})
    with pytest.raises(ValueError, match="signal"):
        sim.set_signal(1, {"kind": "sine"})
    with pytest.raises(ValueError, match="t_end"):
        sim.run_to(float("nan"))
