"""Reference timing: scipy's eigsh (ARPACK shift-invert) on the tire matrices exported by
`tire_modes --export DIR`. Usage: python3 eigsh_tire.py DIR [nev]

Prints the matrix-read time, the eigsh time (factorization + Lanczos, default ncv) and the
lowest frequencies, for comparison with fe-model's sparse_modes (BENCHMARKS.md)."""
import sys
import time

import numpy as np
import scipy.io
import scipy.sparse.linalg as sla

d = sys.argv[1]
nev = int(sys.argv[2]) if len(sys.argv) > 2 else 50
t0 = time.perf_counter()
K = scipy.io.mmread(f"{d}/K.mtx").tocsc()
M = scipy.io.mmread(f"{d}/M.mtx").tocsc()
t1 = time.perf_counter()
vals, vecs = sla.eigsh(K, k=nev, M=M, sigma=0.0, which="LM")
t2 = time.perf_counter()
vals = np.sort(vals)
f = np.sqrt(np.abs(vals)) / (2 * np.pi)
print(f"scipy {__import__('scipy').__version__}: n = {K.shape[0]}, nnz(K) = {K.nnz}")
print(f"read {t1 - t0:.2f} s, eigsh(k={nev}, sigma=0) {t2 - t1:.2f} s")
print("frequencies [Hz]:", " ".join(f"{x:.3f}" for x in f))
