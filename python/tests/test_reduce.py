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
