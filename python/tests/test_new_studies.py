"""Studies new to Python (issue 39 item 5): the wrapped string (``flowmbd.string.wrap``) and
the slider-crank demonstration (``flowmbd.belt.demo``): the CLI's numbers, an independent
reference each, and bad input."""

import flowmbd
import numpy as np
import pytest
from compare import assert_same

SHORT = {"duration": 0.02, "vtk_snapshots": 0}


def test_wrap_equals_cli(cli, tmp_path):
    (tmp_path / "c.toml").write_text("duration = 0.02\nvtk_snapshots = 0\n")
    code, ref, err = cli("string", "wrap", "--config", str(tmp_path / "c.toml"))
    assert code == 0, err
    py = flowmbd.string.wrap(config=SHORT, series=True)
    h, events = py.pop("history"), py.pop("events")
    assert_same(py, ref)
    assert h["t_s"][0] == 0.0 and h["t_s"][-1] <= 0.02 + 1e-12
    assert set(events) == {
        "t_s", "candidate_index", "node_index", "activated_flag", "impact_loss_J"
    }


def test_static_wrap_force_matches_tangent_geometry():
    # Reference: a string at tension T over a convex pulley of radius R whose top lies d above
    # the anchors' line, the anchor x_c from the pulley centre. In the parabolic (small-slope)
    # approximation the straight segment from the anchor touches the pulley a = x_c − √(x_c² −
    # 2 d R) before the top, and the pulley carries the kink of the string: Σp = T a / R per
    # pulley (the other side, between the equal pulleys, is level). Defaults: T = 1000 N,
    # x_c = 0.1 m, d = 0.015 m, R = 0.25 m: a = 0.05 m, Σp = 200 N; nodes 0.01 m apart.
    r = flowmbd.string.wrap(config=SHORT)
    a = 0.1 - (0.1**2 - 2 * 0.015 * 0.25) ** 0.5
    expect = 1000.0 * a / 0.25
    for f in r["initial_force_per_pulley"]:
        assert abs(f - expect) < 0.1 * expect, (f, expect)
    assert all(n > 0 for n in r["initial_active_per_pulley"])


def test_wrap_rejects_a_supercritical_speed():
    # above c = √(T/ρA) the string between fixed supports is no initial-value problem
    with pytest.raises(ValueError, match="speed"):
        flowmbd.string.wrap(config=SHORT, speed=100.0)
    with pytest.raises(ValueError, match=r"pulleys\[0\]\.radius"):
        flowmbd.string.wrap(config={"pulleys": [{"center_x": 0.1, "top": 0.0, "radius": -1.0}]})


def test_demo_equals_cli_and_the_closed_form(cli):
    # the slider-crank demonstration (flowmbd-belt demo), shortened; reference for the numbers:
    # the closed-form slider position x = a cos θ + √(b² − a² sin² θ) in its own series
    code, ref, err = cli("belt", "demo", "--t-end", "0.2")
    assert code == 0, err
    py = flowmbd.belt.demo(t_end=0.2, series=True)
    h = py.pop("history")
    assert_same(py, ref)
    a, b = 0.1, 0.3
    closed = a * np.cos(h["theta_rad"]) + np.sqrt(b**2 - (a * np.sin(h["theta_rad"])) ** 2)
    np.testing.assert_allclose(h["closed_form_x_m"], closed, rtol=1e-12)
    assert np.max(np.abs(h["slider_x_m"] - closed)) == pytest.approx(py["max_slider_error_m"])
    assert py["max_slider_error_m"] < 1e-3 * a
    with pytest.raises(ValueError, match="rod_length"):
        flowmbd.belt.demo(config={"rod_length": 0.05})
