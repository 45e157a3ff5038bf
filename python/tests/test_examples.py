"""The Python examples that run in seconds are run here, so that they cannot rot:
``python/examples/tire_steady_curves.py`` (issue 38: the steady study of the small tire with a
prescribed-slip sweep, F_x(kappa), F_y(alpha), M_z(alpha)). References: its configuration is
``apps/tire/examples/small-tire-steady.toml`` (compared key by key), its CSV files hold the
summary's own numbers, and the curves have the signs and the bound of Coulomb friction that the
physics fixes (independent of the model's numbers)."""

import csv
import importlib.util
import pathlib
import tomllib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def _load(name):
    spec = importlib.util.spec_from_file_location(name, ROOT / "python" / "examples" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _rows(path):
    with open(path) as f:
        r = list(csv.reader(f))
    return r[0], [[float(x) for x in row] for row in r[1:]]


def test_tire_steady_curves_example(tmp_path):
    ex = _load("tire_steady_curves")
    # the example's dict is the shipped TOML example (less the reduced_file the package ignores)
    toml = tomllib.loads((ROOT / "apps/tire/examples/small-tire-steady.toml").read_text())
    toml["tire"].pop("reduced_file")
    assert ex.CONFIG == toml
    summary, paths = ex.main(["--out", str(tmp_path)])
    names = sorted(p.name for p in paths)
    try:
        import matplotlib  # noqa: F401

        assert names == ["fx_kappa.csv", "fy_mz_alpha.csv", "tire_steady_curves.png"]
        assert (tmp_path / "tire_steady_curves.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    except ImportError:
        assert names == ["fx_kappa.csv", "fy_mz_alpha.csv"]
    head, fx = _rows(tmp_path / "fx_kappa.csv")
    assert head == ["kappa_ratio", "fx_N", "spin_torque_N_m"]
    assert len(fx) == len(ex.SLIP_RATIOS)
    # the prescribed slips are held (measured from the settled spin)
    for (k, _, _), want in zip(fx, sorted(ex.SLIP_RATIOS)):
        assert k == pytest.approx(want, abs=1e-6)
    fz = summary["free_rolling_fz_n"]
    mu = summary["friction"]
    for k, f, tau in fx:
        # driving (kappa > 0) pushes the wheel forward, braking back; the torque holding the
        # spin has the sign of the force it makes (drive or brake); |Fx| <= mu Fz (Coulomb;
        # 2 % for the spindle's inertia over the averaging window)
        assert f * k > 0 and tau * k > 0, (k, f, tau)
        assert abs(f) <= 1.02 * mu * fz
    head, lat = _rows(tmp_path / "fy_mz_alpha.csv")
    assert head == ["slip_angle_deg", "fy_N", "mz_N_m"]
    assert [r[0] for r in lat] == sorted(ex.CONFIG["slip_angles_deg"])
    c = summary["cornering_stiffness_n_per_rad"]
    for a, fy, _ in lat:
        # the side force has the sign of C alpha, bounded by Coulomb
        assert fy * a * c > 0 and abs(fy) <= 1.02 * mu * fz
    # the CSV holds the summary's numbers, paired by slip angle
    want = sorted(zip(summary["slip_angle_deg"], summary["fy_n"], summary["mz_n_m"]))
    assert lat == [list(w) for w in want]
