#!/usr/bin/env bash
# Installs the peer of `fe-model/benches/eigen_vs_scipy.rs` into the venv given as $1 (outside
# the repository): scipy (PyPI wheel, ARPACK) and scikit-sparse 0.4.15 (CHOLMOD), with CHOLMOD
# on OpenBLAS.
#
# CHOLMOD comes from Debian (libsuitesparse-dev, SuiteSparse 5.12; scikit-sparse 0.5 needs
# SuiteSparse 7 and has no wheel). Debian's libcholmod3 links the generic libblas.so.3 /
# liblapack.so.3, which the alternatives system points to OpenBLAS once libopenblas0-pthread is
# installed (priority 100 against 10 for the reference BLAS): without it CHOLMOD runs on the
# reference (netlib) BLAS. The script installs it and checks where libblas.so.3 resolves.
# ARPACK and scipy's dense kernels use the OpenBLAS bundled in scipy's wheel. Both OpenBLAS
# copies and CHOLMOD's OpenMP obey OPENBLAS_NUM_THREADS / OMP_NUM_THREADS, which the bench sets.
set -euo pipefail
venv=${1:?usage: setup_eigsh.sh VENV}
need=()
for p in libsuitesparse-dev libopenblas0-pthread libopenblas-dev python3-venv; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || need+=("$p")
done
if ((${#need[@]})); then
    if [ "$(id -u)" != 0 ]; then
        echo "setup_eigsh.sh: install ${need[*]} (apt-get, as root) first" >&2
        exit 1
    fi
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need[@]}" >/dev/null
fi
blas=$(readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3)
lapack=$(readlink -f /usr/lib/x86_64-linux-gnu/liblapack.so.3)
case "$blas$lapack" in
*openblas*openblas*) ;;
*)
    echo "setup_eigsh.sh: libblas.so.3 -> $blas, liblapack.so.3 -> $lapack: not OpenBLAS" >&2
    echo "  (update-alternatives --config libblas.so.3-x86_64-linux-gnu)" >&2
    exit 1
    ;;
esac
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
"$venv/bin/pip" install -q numpy scipy threadpoolctl cython setuptools wheel
"$venv/bin/python" -c "import sksparse.cholmod" 2>/dev/null ||
    "$venv/bin/pip" install -q --no-build-isolation "scikit-sparse==0.4.15"
so=$("$venv/bin/python" -c "import sksparse.cholmod as c; print(c.__file__)")
echo "scikit-sparse: $so"
ldd "$so" | grep -E "cholmod|blas|lapack|gomp" | sed 's/^/  /'
echo "libblas.so.3 -> $blas"
echo "liblapack.so.3 -> $lapack"
