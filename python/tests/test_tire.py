"""flowmbd.tire: the reduced tire as a reusable, picklable object and the cleat test.

References: the CLI (`flowmbd-tire reduce` and `flowmbd-tire cleat --json`, which call the same
library functions through the app layer) to 1e-12; the same run with the unpickled tire (a
bit-identical round trip); an imported copy of the generated tire (Matrix Market and ABAQUS
files written here from the generated matrices), whose reduction must give the generated
tire's frequencies (the library test `tests/tests/tire_import.rs` does the same in Rust)."""

import json
import pickle

import numpy as np
import pytest
import scipy.io
import scipy.sparse as sp

import flowmbd
from compare import assert_same
from tire_case import RIG, RIG_TOML, TIRE, TIRE_TOML

MATRICES = ("m", "k", "g1", "g2", "k1", "kr", "kr1", "kt", "kt1", "tc", "tc_theta",
            "p_e", "p_e1", "p_e2", "m_theta", "c_s", "contact_positions", "free_mode_hz",
            "contact_mode_hz")


def write_config(tmp_path, reduced_file, rig=True):
    """The CLI's configuration file: the tire tables (reduced file `reduced_file`), with the
    short rig for `cleat` (`rig`)."""
    p = tmp_path / ("cleat.toml" if rig else "tire.toml")
    p.write_text((RIG_TOML if rig else "") + f"[tire]\nreduced_file = {str(reduced_file)!r}\n"
                 + TIRE_TOML)
    return p


def test_reduction_equals_the_cli_file(cli, tmp_path, reduced):
    cfg = write_config(tmp_path, tmp_path / "reduced.json", rig=False)
    code, summary, err = cli("tire", "reduce", "--config", str(cfg))
    assert code == 0, err
    ref = flowmbd.tire.ReducedTire.load(summary["file"])
    assert (reduced.n_contact, reduced.n_free_modes, reduced.dof) == (33, 50, summary["dof"])
    assert reduced.source == ref.source  # same fingerprint: the CLI would reuse a saved copy
    for name in MATRICES:
        a, b = getattr(reduced, name), getattr(ref, name)
        np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-12 * np.abs(b).max(), err_msg=name)
    np.testing.assert_array_equal(reduced.contact_nodes, ref.contact_nodes)
    assert reduced.tire_mass == pytest.approx(summary["tire_mass_kg"], rel=1e-12)


def test_cleat_with_the_reduced_tire_equals_the_cli(cli, tmp_path, reduced):
    # the CLI reduces the same tire itself (reduced_file "" : never saved, never reused)
    cfg = write_config(tmp_path, "")
    code, ref, err = cli("tire", "cleat", "--speed", "60", "--config", str(cfg))
    assert code == 0, err
    py = flowmbd.tire.cleat(speed_kmh=60.0, config=RIG, tire=reduced)
    assert_same(py, ref)
    assert py["steps"] == 500 and py["dof"] == 6 + 3 * 33 + 50  # Ribaric §8.2 DOF count
    # without tire= the function reduces config["tire"] itself: the same numbers
    assert_same(flowmbd.tire.cleat(speed_kmh=60.0, config={**RIG, "tire": TIRE}), ref)


def test_cleat_phases_equal_the_cli(cli, tmp_path, reduced):
    # `cleat_phases = 2`: the CLI's `phases` (phase 0 = the run itself, phase 1 = the cleat half
    # an impact step later) to 1e-12
    cfg = write_config(tmp_path, "")
    code, ref, err = cli("tire", "cleat", "--speed", "60", "--phases", "2", "--config", str(cfg))
    assert code == 0, err
    py = flowmbd.tire.cleat(speed_kmh=60.0, config={**RIG, "cleat_phases": 2}, tire=reduced)
    assert_same(py, ref)
    assert py["phases"]["phases"] == 2
    assert py["phases"]["fy_band_rms_n"][0] == pytest.approx(py["fy_band_rms_n"], rel=1e-12)


def test_pickle_round_trip(reduced):
    back = pickle.loads(pickle.dumps(reduced))
    assert isinstance(back, flowmbd.tire.ReducedTire)
    for name in MATRICES:
        np.testing.assert_array_equal(getattr(back, name), getattr(reduced, name), err_msg=name)
    assert back.source == reduced.source
    # reference: the same cleat run with the original object
    a = flowmbd.tire.cleat(60.0, RIG, tire=reduced, series=True)
    b = flowmbd.tire.cleat(60.0, RIG, tire=back, series=True)
    assert_same(b, a)
    np.testing.assert_allclose(b["forces"]["fy_N"], a["forces"]["fy_N"], rtol=1e-12)
    # the history's vertical force before the cleat carries the preload (Ribaric §8.3: the
    # rolling tire is in equilibrium), within 2 %, before the cleat enters the patch
    before = a["forces"]["t_s"] < -0.02
    assert before.sum() > 50
    assert abs(a["forces"]["fy_N"][before].mean() / a["load_n"] - 1.0) < 0.02


def test_save_and_load(tmp_path, reduced):
    reduced.save(tmp_path / "r.json")
    back = flowmbd.tire.ReducedTire.load(tmp_path / "r.json")
    np.testing.assert_array_equal(back.k, reduced.k)
    # the reduced pair's lowest frequency equals the one computed from the numpy matrices
    import scipy.linalg as la
    lam = la.eigh(reduced.k, reduced.m, eigvals_only=True)
    np.testing.assert_allclose(reduced.frequencies_hz()[:5], np.sqrt(lam[:5]) / (2 * np.pi),
                               rtol=1e-9)


def test_load_refuses_devices_and_changed_files(tmp_path, reduced):
    # issue #35: `ReducedTire.load('/dev/zero')` read without end; a file whose `k` was doubled
    # (valid JSON) was used. Reference: the saved file itself loads bit-identically.
    with pytest.raises(ValueError, match="not a regular file"):
        flowmbd.tire.ReducedTire.load("/dev/zero")
    reduced.save(tmp_path / "r.json")
    np.testing.assert_array_equal(flowmbd.tire.ReducedTire.load(tmp_path / "r.json").k, reduced.k)
    doc = json.loads((tmp_path / "r.json").read_text())
    doc["tire"]["k"]["data"] = [2.0 * v for v in doc["tire"]["k"]["data"]]
    (tmp_path / "k2.json").write_text(json.dumps(doc))
    with pytest.raises(ValueError, match="checksum mismatch"):
        flowmbd.tire.ReducedTire.load(tmp_path / "k2.json")
    assert reduced.code_version.startswith("flowmbd ")


def test_generate_and_import_give_the_same_reduced_tire(tmp_path, reduced):
    fe = flowmbd.tire.generate(TIRE["generator"])
    n = fe["nodes"].shape[0]
    assert fe["K"].shape == (3 * n, 3 * n) and fe["M"].shape == (3 * n, 3 * n)
    assert abs(fe["K"] - fe["K"].T).max() <= 1e-9 * abs(fe["K"]).max()
    # Matrix Market (0-based node indices)
    scipy.io.mmwrite(tmp_path / "K.mtx", sp.coo_matrix(fe["K"]), symmetry="symmetric",
                     precision=17)
    scipy.io.mmwrite(tmp_path / "M.mtx", sp.coo_matrix(fe["M"]), symmetry="symmetric",
                     precision=17)
    np.savetxt(tmp_path / "nodes.txt", fe["nodes"], fmt="%.17g", delimiter=", ")
    np.savetxt(tmp_path / "rim.txt", fe["rim_nodes"], fmt="%d")
    np.savetxt(tmp_path / "patch.txt", fe["patch_nodes"], fmt="%d")
    mm = {"format": "matrix_market", "stiffness": str(tmp_path / "K.mtx"),
          "mass": str(tmp_path / "M.mtx"), "nodes": str(tmp_path / "nodes.txt"),
          "rim_nodes": str(tmp_path / "rim.txt"), "patch_nodes": str(tmp_path / "patch.txt")}
    imp = flowmbd.tire.import_model(mm)
    assert abs(imp["K"] - fe["K"]).max() <= 1e-12 * abs(fe["K"]).max()
    np.testing.assert_allclose(imp["mass"], fe["mass"], rtol=1e-12)
    # ABAQUS *MATRIX GENERATE (node labels 1..n, one triangle, DOFs 1-3)
    labels = np.arange(1, n + 1)
    for name, a in (("K.mtx", fe["K"]), ("M.mtx", fe["M"])):
        t = sp.triu(sp.coo_matrix(a)).tocoo()
        rows = np.column_stack([t.row // 3 + 1, t.row % 3 + 1, t.col // 3 + 1, t.col % 3 + 1])
        with open(tmp_path / f"abq_{name}", "w") as f:
            f.write("** written by test_tire.py\n")
            for (n1, d1, n2, d2), v in zip(rows, t.data):
                f.write(f"{n1},{d1}, {n2},{d2}, {v:.17g}\n")
    np.savetxt(tmp_path / "abq_nodes.inp", np.column_stack([labels, fe["nodes"]]),
               fmt=["%d", "%.17g", "%.17g", "%.17g"], delimiter=", ")
    np.savetxt(tmp_path / "abq_rim.inp", fe["rim_nodes"] + 1, fmt="%d")
    np.savetxt(tmp_path / "abq_patch.inp", fe["patch_nodes"] + 1, fmt="%d")
    abq = {"format": "abaqus", "stiffness": str(tmp_path / "abq_K.mtx"),
           "mass": str(tmp_path / "abq_M.mtx"), "nodes": str(tmp_path / "abq_nodes.inp"),
           "rim_nodes": str(tmp_path / "abq_rim.inp"),
           "patch_nodes": str(tmp_path / "abq_patch.inp")}
    f_gen = reduced.frequencies_hz()[:20]
    for files in (mm, abq):
        red = flowmbd.tire.reduce({"import": files, "reduction": TIRE["reduction"]})
        assert red.n_contact == 33 and "import" in red.source
        np.testing.assert_allclose(red.frequencies_hz()[:20], f_gen, rtol=1e-9)


def test_bad_input_raises_value_error_with_the_cli_message(cli, tmp_path, reduced):
    cfg = write_config(tmp_path, "")
    code, _, err = cli("tire", "cleat", "--speed=-5", "--config", str(cfg))
    assert code == 2
    with pytest.raises(ValueError) as e:
        flowmbd.tire.cleat(speed_kmh=-5.0, config=RIG, tire=reduced)
    assert str(e.value) == "rig.speed_kmh: must be finite and > 0 km/h, got -5"
    assert str(e.value) in err
    # a missing import file: the CLI's message
    (tmp_path / "imp.toml").write_text(
        '[tire.import]\nstiffness = "none.mtx"\nmass = "none.mtx"\nnodes = "n"\n'
        'rim_nodes = "r"\npatch_nodes = "p"\n')
    code, _, err = cli("tire", "reduce", "--config", str(tmp_path / "imp.toml"))
    assert code == 2
    with pytest.raises(ValueError) as e:
        flowmbd.tire.reduce({"import": {"stiffness": "none.mtx", "mass": "none.mtx",
                                        "nodes": "n", "rim_nodes": "r", "patch_nodes": "p"}})
    assert str(e.value) == "tire.import.stiffness: file `none.mtx` does not exist"
    assert str(e.value) in err
    with pytest.raises(ValueError, match="tire.reduction.contact_nodes"):
        flowmbd.tire.reduce({**TIRE, "reduction": {"contact_nodes": 0}})
    with pytest.raises(ValueError, match="unknown field `speed`"):
        flowmbd.tire.cleat(config={"rig": {"speed": 3.0}}, tire=reduced)
    with pytest.raises(ValueError, match="tire: given both"):
        flowmbd.tire.cleat(config={"tire": TIRE}, tire=reduced)
    with pytest.raises(ValueError, match="tire: expected a flowmbd.tire.ReducedTire"):
        flowmbd.tire.cleat(tire="reduced.json")
    with pytest.raises(ValueError, match="tire.generator.circumferential_divisions"):
        flowmbd.tire.generate({"circumferential_divisions": 1000000000})
    with pytest.raises(ValueError, match="reduced tire file JSON text: field `format`"):
        flowmbd.tire.ReducedTire.from_json('{"format": "something else"}')


def test_steady_equals_the_cli(cli, tmp_path, reduced):
    # reference: flowmbd-tire steady on the same tire (reduced by the CLI itself) and inputs
    cfg = tmp_path / "steady.toml"
    cfg.write_text("slip_angles_deg = [-0.1, 0.1]\ndrive_torques_n_m = []\npoint_time = 0.08\n"
                   "average_time = 0.02\n" + f"[tire]\nreduced_file = ''\n" + TIRE_TOML)
    code, ref, err = cli("tire", "steady", "--config", str(cfg))
    assert code == 0, err
    py = flowmbd.tire.steady(config={"slip_angles_deg": [-0.1, 0.1], "drive_torques_n_m": [],
                                     "point_time": 0.08, "average_time": 0.02}, tire=reduced)
    # the .tir text is Python's alone (the CLI writes tire.tir); two points give no fit
    assert py.pop("tir_text") is None
    assert_same(py, ref)
    # the mirrored pair: Fy odd in the slip angle (symmetric tire)
    assert py["fy_n"][0] == pytest.approx(-py["fy_n"][1], rel=1e-9)
