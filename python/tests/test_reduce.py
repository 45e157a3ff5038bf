"""flowmbd.reduce on scipy.sparse matrices: round trip through the native layer and
comparison with independent dense references (scipy.linalg.eigh, numpy projections)."""

import numpy as np
import pytest
import scipy.linalg as la
import scipy.sparse as sp

import flowmbd


def chain(n=40):
    """Fixed-free spring–mass chain with graded masses and stiffnesses (SPD K and M)."""
    k = 1000.0 * (1.0 + 0.1 * np.arange(n))
    m = 1.0 + 0.05 * np.arange(n)
    main = k + np.append(k[1:], 0.0)
    K = sp.diags([main, -k[1:], -k[1:]], [0, 1, -1], format="csr")
    M = sp.diags(m, 0, format="csc")
    return M, K


def test_modes_equal_dense_eigh_in_every_sparse_format():
    M, K = chain()
    ref = la.eigh(K.toarray(), M.toarray(), eigvals_only=True)[:8]  # independent reference
    for fmt in ("csr", "csc", "coo", "lil"):
        r = flowmbd.reduce.modes(M.asformat(fmt), K.asformat(fmt), count=8)
        np.testing.assert_allclose(r["eigenvalues"], ref, rtol=1e-9)
        np.testing.assert_allclose(r["frequencies_hz"], np.sqrt(ref) / (2 * np.pi), rtol=1e-9)
        phi = r["vectors"]
        assert phi.shape == (40, 8)
        np.testing.assert_allclose(phi.T @ M.toarray() @ phi, np.eye(8), atol=1e-9)


def test_fixed_dofs_are_clamped():
    M, K = chain()
    fixed = [39, 0]
    r = flowmbd.reduce.modes(M, K, count=5, fixed=fixed)
    free = [i for i in range(40) if i not in fixed]
    Kd, Md = K.toarray()[np.ix_(free, free)], M.toarray()[np.ix_(free, free)]
    np.testing.assert_allclose(r["eigenvalues"], la.eigh(Kd, Md, eigvals_only=True)[:5], rtol=1e-9)
    assert np.all(r["vectors"][fixed, :] == 0.0)


def test_craig_bampton_round_trip():
    M, K = chain()
    boundary = [0, 20, 39]
    r = flowmbd.reduce.craig_bampton(M, K, boundary=boundary, modes=6)
    psi = r["basis"]
    assert psi.shape == (40, 9) and r["M"].shape == (9, 9)
    # Galerkin projection (Lin (6.20)) recomputed in numpy from the returned basis
    np.testing.assert_allclose(r["M"], psi.T @ M.toarray() @ psi, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(r["K"], psi.T @ K.toarray() @ psi, rtol=1e-9, atol=1e-6)
    # Ψ = I on the boundary DOFs (Lin (6.19))
    np.testing.assert_allclose(psi[boundary, :3], np.eye(3), atol=1e-14)
    # frequencies of the reduced pair
    lam = la.eigh(r["K"], r["M"], eigvals_only=True)
    np.testing.assert_allclose(r["frequencies_hz"], np.sqrt(lam) / (2 * np.pi), rtol=1e-8)
    # the lowest reduced frequency bounds the full one from above (Rayleigh–Ritz)
    full = la.eigh(K.toarray(), M.toarray(), eigvals_only=True)
    assert lam[0] >= full[0] * (1 - 1e-12)


def test_guyan_is_the_schur_complement():
    M, K = chain()
    b = [5, 30]
    r = flowmbd.reduce.craig_bampton(M, K, boundary=b, modes=0)
    Kd = K.toarray()
    i = [j for j in range(40) if j not in b]
    schur = Kd[np.ix_(b, b)] - Kd[np.ix_(b, i)] @ np.linalg.solve(Kd[np.ix_(i, i)], Kd[np.ix_(i, b)])
    np.testing.assert_allclose(r["K"], schur, rtol=1e-9)


def test_all_interior_modes_reproduce_the_full_model():
    M, K = chain(12)
    r = flowmbd.reduce.craig_bampton(M, K, boundary=[0], modes=11)
    full = la.eigh(K.toarray(), M.toarray(), eigvals_only=True)
    np.testing.assert_allclose(np.sort(r["frequencies_hz"]), np.sqrt(full) / (2 * np.pi), rtol=1e-8)


@pytest.mark.parametrize("count", [-1, 1.5])
def test_bad_count(count):
    M, K = chain(5)
    with pytest.raises(ValueError, match="count"):
        flowmbd.reduce.modes(M, K, count=count)


def test_eitelberg_is_guyan():
    # Lin §6.6.4: Eitelberg's M⁻¹K on the boundary equals Guyan's; reference: Guyan by numpy,
    # the Schur complement K_bb − K_bi K_ii⁻¹ K_ib and the projected mass
    M, K = chain(30)
    b = [5, 12, 29]
    r = flowmbd.reduce.eitelberg(M, K, boundary=b, fixed=[0])
    Kd, Md = K.toarray(), M.toarray()
    keep = [i for i in range(30) if i != 0]
    Kd, Md = Kd[np.ix_(keep, keep)], Md[np.ix_(keep, keep)]
    bb = [keep.index(i) for i in b]
    ii = [j for j in range(29) if j not in bb]
    psi = np.zeros((29, 3))
    psi[bb, :] = np.eye(3)
    psi[ii, :] = -np.linalg.solve(Kd[np.ix_(ii, ii)], Kd[np.ix_(ii, bb)])
    kg, mg = psi.T @ Kd @ psi, psi.T @ Md @ psi
    np.testing.assert_allclose(r["minv_k"], np.linalg.solve(mg, kg), rtol=1e-7, atol=1e-9 * abs(kg).max())
    lam = la.eigh(kg, mg, eigvals_only=True)
    np.testing.assert_allclose(r["frequencies_hz"], np.sqrt(lam) / (2 * np.pi), rtol=1e-8)
    assert r["A"].shape == (6, 6) and r["B"].shape == (6, 3) and r["C"].shape == (6, 6)
    with pytest.raises(ValueError, match="boundary"):
        flowmbd.reduce.eitelberg(M, K, boundary="5")


def _csv_equal(series, path):
    csv = np.genfromtxt(path, delimiter=",", names=True)
    assert list(series) == list(csv.dtype.names)
    for k in series:
        np.testing.assert_allclose(series[k], csv[k], rtol=1e-9, atol=1e-300, err_msg=k)


def test_lin_beam_equals_cli(cli, tmp_path):
    from compare import assert_same

    code, ref, err = cli("reduce", "lin-beam")
    assert code == 0, err
    py = flowmbd.reduce.lin_beam(series=True)
    profiles, frequencies = py.pop("profiles"), py.pop("frequencies")
    assert_same(py, ref)
    _csv_equal(profiles, tmp_path / "reduce" / "profiles.csv")
    _csv_equal(frequencies, tmp_path / "reduce" / "frequencies.csv")


def test_lin_beam_matches_lin_6_2_1():
    # Lin §6.2.1 (printed to 6 significant digits): full beam, 3 rigid modes, first bending
    # 5.94776 Hz, first axial 66.7191 Hz; Guyan model (a), masters 1, 3, 5: 5.95823 Hz
    py = flowmbd.reduce.lin_beam()
    f = py["free_free_hz"]
    assert np.all(f[:3] < 1e-3)
    assert abs(f[3] - 5.94776) <= 0.5e-5 and abs(f[6] - 66.7191) <= 0.5e-4
    assert abs(py["guyan_a_hz"][0] - 5.95823) <= 0.5e-5


def test_lin_beam_bad_input_names_the_field():
    with pytest.raises(ValueError, match=r"beam\.length_m"):
        flowmbd.reduce.lin_beam({"beam": {"length_m": -1.0}})
    with pytest.raises(ValueError, match="profile_delta_m"):
        flowmbd.reduce.lin_beam({"profile_delta_m": [0.0] * 9})


SLAB = {"simulations": ["no-rigid-motion", "emulated"], "params": {"duration_s": 0.02}}
SLAB_TOML = 'simulations = ["no-rigid-motion", "emulated"]\n[params]\nduration_s = 0.02\n'


def test_lin_slab_equals_cli(cli, tmp_path):
    from compare import assert_same

    (tmp_path / "c.toml").write_text(SLAB_TOML)
    code, ref, err = cli("reduce", "lin-slab", "--config", str(tmp_path / "c.toml"))
    assert code == 0, err
    py = flowmbd.reduce.lin_slab(SLAB, series=True)
    names = ["sim1_node8", "sim3_node8", "sim3_tables", "sim3_source_node8"]
    series = {k: py.pop(k) for k in names}
    assert_same(py, ref)
    for k in names:
        _csv_equal(series[k], tmp_path / "reduce" / f"{k}.csv")


def test_lin_slab_statics_and_cb_equals_mc():
    # companion §14.6 [D] (Lin §7.2.2): gravity statics of node 8, NR (0.001691, -0.017142,
    # 0.005213) m and CB = MC (..., 0.005120) m; Lin §6.5.4: CB and MC span the same space, so
    # their histories agree up to round-off
    py = flowmbd.reduce.lin_slab({"simulations": ["no-rigid-motion"], "params": {"duration_s": 0.02}})
    s = py["sim1_statics_m"]
    np.testing.assert_allclose(s["NR"], [0.001691, -0.017142, 0.005213], rtol=0, atol=5e-7)
    np.testing.assert_allclose(s["CB"], [0.001691, -0.017142, 0.005120], rtol=0, atol=5e-7)
    assert py["cb_mc_max_difference_m"]["sim1"] < 1e-9


def test_lin_slab_bad_input_names_the_field():
    with pytest.raises(ValueError, match="methods"):
        flowmbd.reduce.lin_slab({"methods": ["guyan"]})


# the small generated tire of the tire tests (tire_case.TIRE: 96 x 8 elements, isotropic tread)
TIRE_MESH_TOML = """
[tire]
circumferential_divisions = 96
section_divisions = 8
thickness_divisions = 1
bead_elements = 1
patch_half_angle_deg = 20.0
[tire.tread]
young = 150e6
poisson = 0.45
density = 1500.0
[tire.carcass]
modulus = 0.0
"""


def _tire_mesh_config():
    from tire_case import TIRE

    return {"tire": TIRE["generator"]}


def test_tire_mesh_equals_cli(cli, tmp_path):
    import scipy.io

    from compare import assert_same

    (tmp_path / "c.toml").write_text(TIRE_MESH_TOML)
    code, ref, err = cli("reduce", "tire-mesh", "--config", str(tmp_path / "c.toml"))
    assert code == 0, err
    py = flowmbd.reduce.tire_mesh(_tire_mesh_config())
    K, M, nodes, sets = (py.pop(k) for k in ("K", "M", "coordinates", "node_set_nodes"))
    ref.pop("files")
    assert_same(py, ref)
    out = tmp_path / "reduce"
    for name, a in (("K", K), ("M", M)):
        b = sp.csc_matrix(scipy.io.mmread(out / f"{name}.mtx"))
        assert abs(a - b).max() <= 1e-15 * abs(b).max(), name
    assert nodes.shape == (py["nodes"], 3) and K.shape == (py["dof"], py["dof"])
    import json

    ref_sets = json.loads((out / "node_sets.json").read_text())
    assert set(sets) == set(ref_sets)
    for k in sets:
        np.testing.assert_array_equal(sets[k], ref_sets[k])
        assert len(sets[k]) == py["node_sets"][k]


def test_tire_mesh_mass_and_stiffness_match_tire_generate():
    # independent discretisation of the same body: the consistent mass (tire-mesh default) and
    # the lumped mass of flowmbd.tire.generate both carry the total mass rho V of the carcass;
    # K (with the inflation prestress) is the same matrix
    config = _tire_mesh_config()
    py = flowmbd.reduce.tire_mesh(config)
    gen = flowmbd.tire.generate(config["tire"])
    lumped_total = gen["mass"][0::3].sum()
    assert abs(py["mass_kg"] / lumped_total - 1.0) < 1e-9
    u = np.zeros(py["dof"])
    u[0::3] = 1.0
    assert abs(u @ (py["M"] @ u) / py["mass_kg"] - 1.0) < 1e-12
    assert abs(py["K"] - gen["K"]).max() <= 1e-12 * abs(gen["K"]).max()
    np.testing.assert_array_equal(py["node_set_nodes"]["rim"], gen["rim_nodes"])


def test_tire_mesh_bad_input_names_the_field():
    with pytest.raises(ValueError, match=r"tire\.section_divisions"):
        flowmbd.reduce.tire_mesh({"tire": {"section_divisions": 2}})
