"""Peer timing for the `mtx_read` bench: scipy.io.mmread of K.mtx and M.mtx in DIR, alone
(COO result) and followed by `.tocsc()`; best of REPEAT runs. Prints one line
`scipy <version> read <s> csc <s>` for the Rust bench to parse.
Usage: python3 mmread.py DIR [REPEAT]"""
import sys
import time

import scipy
import scipy.io

d = sys.argv[1]
repeat = int(sys.argv[2]) if len(sys.argv) > 2 else 3
best_read = best_csc = float("inf")
for _ in range(repeat):
    t0 = time.perf_counter()
    k = scipy.io.mmread(f"{d}/K.mtx")
    m = scipy.io.mmread(f"{d}/M.mtx")
    t1 = time.perf_counter()
    k, m = k.tocsc(), m.tocsc()
    t2 = time.perf_counter()
    best_read = min(best_read, t1 - t0)
    best_csc = min(best_csc, t2 - t0)
    assert k.shape == m.shape
print(f"scipy {scipy.__version__} read {best_read:.4f} csc {best_csc:.4f}")
