"""Peer of `fe-model/benches/eigen_vs_scipy.rs`: the lowest modes of K φ = λ M φ with scipy's
ARPACK (`eigsh(K, k, M, sigma, mode='normal')`) and a shift-invert operator from CHOLMOD
(scikit-sparse, supernodal Cholesky of K - sigma M) or, when scikit-sparse is missing or
`--superlu` is given, SuperLU with the MMD_AT_PLUS_A ordering.

Usage: python eigsh.py DIR [--nev 50] [--sigma 0] [--tol 0] [--superlu] [--out vals.txt]
Reads DIR/K.mtx and DIR/M.mtx (not timed), then times factorisation + eigsh (eigenvectors
returned) and prints `peer_seconds = T` (wall), `peer_cpu_seconds = T` (process CPU),
`peer_factor_seconds = T`, `peer_solver = NAME`, `peer_solves = N`, `peer_blas = ...` (the
BLAS libraries loaded, their kernel and thread count, from threadpoolctl) and writes the
eigenvalues (ascending, repr) to --out. `--tol` is eigsh's (ARPACK's per-pair test
`‖r_i‖ ≤ tol·|θ_i|`; 0 = machine precision). Thread counts come from the environment
(OPENBLAS_NUM_THREADS, OMP_NUM_THREADS), set by the bench; `--scipy-blas-threads N` then
limits numpy's and scipy's bundled OpenBLAS (scipy-openblas: ARPACK's dense work) to N
threads with threadpoolctl, leaving CHOLMOD's OpenBLAS at OPENBLAS_NUM_THREADS."""
import argparse
import time

import numpy as np
import scipy
import scipy.io
import scipy.sparse.linalg as sla

ap = argparse.ArgumentParser()
ap.add_argument("dir")
ap.add_argument("--nev", type=int, default=50)
ap.add_argument("--sigma", type=float, default=0.0)
ap.add_argument("--tol", type=float, default=0.0)
ap.add_argument("--scipy-blas-threads", type=int, default=None)
ap.add_argument("--superlu", action="store_true")
ap.add_argument("--out", default=None)
a = ap.parse_args()

if a.scipy_blas_threads is not None:
    # numpy's and scipy's bundled OpenBLAS (ARPACK's dense work, the Python-side vector
    # operations) read OPENBLAS_NUM_THREADS like CHOLMOD's OpenBLAS; this sets them apart
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits={"libscipy_openblas": a.scipy_blas_threads})

K = scipy.io.mmread(f"{a.dir}/K.mtx").tocsc()
M = scipy.io.mmread(f"{a.dir}/M.mtx").tocsc()
n = K.shape[0]

solver = "superlu-mmd_at_plus_a"
cholesky = None
if not a.superlu:
    try:
        from sksparse.cholmod import cholesky

        solver = "cholmod"
    except ImportError:
        cholesky = None

count = [0]
t0 = time.perf_counter()
c0 = time.process_time()
A = (K - a.sigma * M).tocsc()
if cholesky is not None:
    F = cholesky(A)

    def solve(b):
        count[0] += 1
        return F(b)

else:
    lu = sla.splu(A, permc_spec="MMD_AT_PLUS_A")

    def solve(b):
        count[0] += 1
        return lu.solve(b)

t1 = time.perf_counter()
op = sla.LinearOperator((n, n), matvec=solve, dtype=np.float64)
vals = sla.eigsh(K, k=a.nev, M=M, sigma=a.sigma, which="LM", mode="normal", OPinv=op,
                 tol=a.tol, return_eigenvectors=True)[0]
t2 = time.perf_counter()
c2 = time.process_time()
vals = np.sort(vals)
print(f"peer_solver = {solver} (scipy {scipy.__version__})")
print(f"peer_factor_seconds = {t1 - t0:.4f}")
print(f"peer_seconds = {t2 - t0:.4f}")
print(f"peer_cpu_seconds = {c2 - c0:.4f}")
print(f"peer_solves = {count[0]}")
try:
    from threadpoolctl import threadpool_info

    blas = [f"{d['filepath'].split('/')[-1]} {d.get('version')} {d.get('architecture')} "
            f"{d['num_threads']} thr" for d in threadpool_info() if d["user_api"] == "blas"]
    omp = [d["num_threads"] for d in threadpool_info() if d["user_api"] == "openmp"]
    print(f"peer_blas = {'; '.join(blas)}; openmp {omp} thr")
except ImportError:
    print("peer_blas = unknown (no threadpoolctl)")
if a.out:
    with open(a.out, "w") as f:
        for v in vals:
            f.write(repr(float(v)) + "\n")
