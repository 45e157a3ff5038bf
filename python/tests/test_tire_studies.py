"""flowmbd.tire studies beyond cleat and steady (issue 39 item 5): each equals the CLI's
`summary.json` for the same configuration, and its series the CLI's CSV files.

References: the `flowmbd-tire` binary (which reduces the same small tire itself, reduced_file
"") run on the same TOML; summaries to 1e-12, series to 1e-9 (the CSV holds 11 significant
digits)."""

import numpy as np
import pytest

import flowmbd
from compare import assert_same
from tire_case import TIRE_TOML


def cli_config(tmp_path, text, name="study.toml"):
    """The CLI's configuration file: `text` (the study's keys) and the small tire, reduced by
    the CLI itself and never saved."""
    p = tmp_path / name
    p.write_text(text + "\n[tire]\nreduced_file = ''\n" + TIRE_TOML)
    return p


def csv_columns(path):
    """The columns of a CSV file written by the CLI (header names as keys)."""
    data = np.genfromtxt(path, delimiter=",", names=True, dtype=float)
    return {n: np.atleast_1d(data[n]) for n in data.dtype.names}


def assert_series(py, path):
    ref = csv_columns(path)
    assert list(py) == list(ref), path.name  # the CSV's header, in order
    for k, col in ref.items():
        np.testing.assert_allclose(py[k], col, rtol=1e-9, atol=1e-300, err_msg=f"{path.name}:{k}")


def test_rotating_modes_equal_the_cli(cli, tmp_path, reduced):
    # same as `flowmbd-tire rotating-modes --speeds 0,60 --json` summary and rotating_modes.csv
    cfg = cli_config(tmp_path, "max_hz = 120.0")
    code, ref, err = cli("tire", "rotating-modes", "--speeds", "0,60", "--config", str(cfg))
    assert code == 0, err
    py = flowmbd.tire.rotating_modes({"max_hz": 120.0}, tire=reduced, speeds_kmh=[0, 60],
                                     series=True)
    series = py.pop("rotating_modes")
    assert_same(py, ref)
    assert_series(series, tmp_path / "tire" / "rotating_modes.csv")
    # at rest every mode stands; rolling splits order 1 in-plane into forward > backward
    assert all(m["direction"] == "standing" for m in py["speeds"][0]["free"])
    n1 = next(s for s in py["splits"] if s["n"] == 1 and s["plane"] == "in_plane")
    assert n1["split_hz"][0] == 0.0 and n1["split_hz"][1] > 0.0
    assert len(series["f_Hz"]) == sum(len(s["free"]) + len(s["loaded"]) for s in py["speeds"])
    # without series=True the result is the summary alone
    assert "rotating_modes" not in flowmbd.tire.rotating_modes(
        {"max_hz": 120.0, "speeds_kmh": [0.0]}, tire=reduced)


def test_rotating_modes_bad_input(cli, tmp_path, reduced):
    cfg = cli_config(tmp_path, "")
    code, _, err = cli("tire", "rotating-modes", "--speeds=-5", "--config", str(cfg))
    assert code == 2
    with pytest.raises(ValueError) as e:
        flowmbd.tire.rotating_modes(tire=reduced, speeds_kmh=[-5.0])
    assert str(e.value) == "speeds_kmh: -5 is not ≥ 0"
    assert str(e.value) in err
    with pytest.raises(ValueError, match=r'config\["ground"\]'):
        flowmbd.tire.rotating_modes({"ground": {"radius": 1.0}}, tire=reduced)
    with pytest.raises(ValueError, match="tire: given both"):
        flowmbd.tire.rotating_modes({"tire": {}}, tire=reduced)


SWEEP_RIG = """
[rig]
settle_time = 0.05
record_time = 0.05
"""


def test_sweep_equals_the_cli(cli, tmp_path, reduced):
    # same as `flowmbd-tire sweep` summary.json, waterfall.csv, fy/fx_matrix.csv and the
    # per-speed forces/spectra CSVs, two speeds on the short rig
    cfg = cli_config(tmp_path, "speeds_kmh = [40.0, 60.0]\n" + SWEEP_RIG)
    code, ref, err = cli("tire", "sweep", "--config", str(cfg))
    assert code == 0, err
    rig = {"rig": {"settle_time": 0.05, "record_time": 0.05}}
    py = flowmbd.tire.sweep(rig, tire=reduced, speeds_kmh=[40.0, 60.0], series=True)
    waterfall, smap, runs = py.pop("waterfall"), py.pop("spectrum_map"), py.pop("run_series")
    assert_same(py, ref)
    out = tmp_path / "tire"
    assert_series(waterfall, out / "waterfall.csv")
    for name in ("fy", "fx"):
        m = np.genfromtxt(out / f"{name}_matrix.csv", delimiter=",", skip_header=1, ndmin=2)
        np.testing.assert_allclose(m[:, 0], smap["speed_km_per_h"], rtol=0)
        np.testing.assert_allclose(smap[f"{name}_amp_N"], m[:, 1:], rtol=1e-9, atol=1e-300)
        head = (out / f"{name}_matrix.csv").read_text().splitlines()[0].split(",")[1:]
        assert head == [f"f{f:.3f}Hz_amp_N" for f in smap["f_Hz"]]
    for v, r in zip((40, 60), runs):
        assert_series(r["forces"], out / f"v{v:03d}_forces.csv")
        assert_series(r["spectra"], out / f"v{v:03d}_spectra.csv")
    # each run is the cleat test at that speed (the sweep's run summaries omit mode labels)
    one = flowmbd.tire.cleat(60.0, {**rig, "vtk_interval": 0, "vtk_tire_interval": 0},
                             tire=reduced)
    assert py["runs"][1]["fy_band_rms_n"] == pytest.approx(one["fy_band_rms_n"], rel=1e-12)
    assert len(py.to_dataframe()) == 2  # one row per speed (the records "runs")


def test_sweep_bad_input(cli, tmp_path, reduced):
    cfg = cli_config(tmp_path, "speeds_kmh = [40.0, 0.0]")
    code, _, err = cli("tire", "sweep", "--config", str(cfg))
    assert code == 2
    with pytest.raises(ValueError) as e:
        flowmbd.tire.sweep(tire=reduced, speeds_kmh=[40.0, 0.0])
    assert str(e.value) == "speeds_kmh[1]: must be positive"
    assert str(e.value) in err
    with pytest.raises(ValueError, match=r'config\["rig"\]\["speed"\]'):
        flowmbd.tire.sweep({"rig": {"speed": 3.0}}, tire=reduced)
    with pytest.raises(ValueError, match=r"speeds_kmh\[0\]: expected a number"):
        flowmbd.tire.sweep(tire=reduced, speeds_kmh=["fast"])


def test_dips_equal_the_cli(cli, tmp_path, reduced):
    # same as `flowmbd-tire dips` summary.json and profile_/prediction_/sweep_road.csv: the
    # road only, a two-speed sweep on the short rig
    cfg = cli_config(tmp_path, 'grounds = ["road"]\n[dips]\nsweep_speeds_kmh = [50.0, 60.0]\n'
                     + SWEEP_RIG)
    code, ref, err = cli("tire", "dips", "--config", str(cfg))
    assert code == 0, err
    config = {"grounds": ["road"], "dips": {"sweep_speeds_kmh": [50.0, 60.0]},
              "rig": {"settle_time": 0.05, "record_time": 0.05}}
    py = flowmbd.tire.dips(config, tire=reduced, series=True)
    series = {k: py.pop(k) for k in ("profile_road", "prediction_road", "sweep_road")}
    assert_same(py, ref)
    for name, cols in series.items():
        assert_series(cols, tmp_path / "tire" / f"{name}.csv")
    g = py["grounds"][0]
    assert g["ground"] == "road" and len(g["line_amplitude_n"]) == 2
    # the predicted dips are minima of the prediction series
    a, v = series["prediction_road"]["amplitude_N"], series["prediction_road"]["speed_km_per_h"]
    for d in g["predicted_dips_kmh"]:
        i = int(np.flatnonzero(v == d)[0])
        assert a[i] < a[i - 1] and a[i] < a[i + 1]


def test_dips_bad_input(cli, tmp_path, reduced):
    cfg = cli_config(tmp_path, "[dips]\nprofile_step = -1.0")
    code, _, err = cli("tire", "dips", "--no-sweep", "--config", str(cfg))
    assert code == 2
    with pytest.raises(ValueError) as e:
        flowmbd.tire.dips({"dips": {"profile_step": -1.0, "sweep_speeds_kmh": []}},
                          tire=reduced)
    assert str(e.value).startswith("dips.profile_step: ")
    assert str(e.value) in err
    with pytest.raises(ValueError, match=r'config\["grounds"\]\[0\]'):
        flowmbd.tire.dips({"grounds": ["moon"]}, tire=reduced)


def test_pressure_equals_the_cli(cli, tmp_path, reduced):
    # same as `flowmbd-tire pressure` summary.json, patch_drum.csv and patch_road.csv
    cfg = cli_config(tmp_path, "load = 3000.0")
    code, ref, err = cli("tire", "pressure", "--config", str(cfg))
    assert code == 0, err
    py = flowmbd.tire.pressure({"load": 3000.0}, tire=reduced, series=True)
    patches = {k: py.pop(k) for k in ("patch_drum", "patch_road")}
    assert_same(py, ref)
    for name, cols in patches.items():
        assert_series(cols, tmp_path / "tire" / f"{name}.csv")
        # the node forces carry the load (static equilibrium, Ribaric §7.3)
        assert cols["force_N"].sum() == pytest.approx(3000.0, rel=1e-6)
    assert py["drum"]["deflection_m"] > py["road"]["deflection_m"]


def test_pressure_bad_input(cli, tmp_path, reduced):
    cfg = cli_config(tmp_path, "drum_radius = -1.0")
    code, _, err = cli("tire", "pressure", "--config", str(cfg))
    assert code == 2
    with pytest.raises(ValueError) as e:
        flowmbd.tire.pressure({"drum_radius": -1.0}, tire=reduced)
    assert str(e.value) == "drum_radius: must be positive"
    assert str(e.value) in err
    with pytest.raises(ValueError, match=r'config\["load"\]'):
        flowmbd.tire.pressure({"load": "heavy"}, tire=reduced)


def test_modes_equal_the_cli(cli, tmp_path):
    # same as `flowmbd-tire modes` summary.json, modes.csv and loaded_modes.csv (both sides
    # build and reduce the small tire themselves)
    from tire_case import TIRE

    cfg = cli_config(tmp_path, "count = 12")
    code, ref, err = cli("tire", "modes", "--config", str(cfg))
    assert code == 0, err
    py = flowmbd.tire.modes({"count": 12, "tire": TIRE}, series=True)
    modes, loaded = py.pop("modes"), py.pop("loaded_modes")
    assert_same(py, ref)
    assert_series(modes, tmp_path / "tire" / "modes.csv")
    assert_series(loaded, tmp_path / "tire" / "loaded_modes.csv")
    # Rayleigh-Ritz: the reduced frequencies bound the full ones from above
    assert np.all(py["reduced_hz"] >= py["full_hz"] * (1 - 1e-9))
    assert len(py["full_hz"]) == 12


def test_modes_bad_input(cli, tmp_path):
    cfg = cli_config(tmp_path, "count = 0")
    code, _, err = cli("tire", "modes", "--config", str(cfg))
    assert code == 2
    with pytest.raises(ValueError) as e:
        flowmbd.tire.modes({"count": 0})
    assert str(e.value) == "count: must be positive"
    assert str(e.value) in err
