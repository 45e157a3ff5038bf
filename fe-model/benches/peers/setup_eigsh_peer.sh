#!/usr/bin/env bash
# Installs the peer of fe-model/benches/eigen_vs_scipy.rs into the venv DIR (first argument;
# keep it outside the repository, e.g. /tmp/eigpeer):
#   - Debian's SuiteSparse 5.12 (CHOLMOD) and OpenBLAS 0.3.21 (pthread build), with the
#     libblas.so.3 / liblapack.so.3 alternatives pointed at OpenBLAS, so that CHOLMOD's
#     supernodal BLAS-3 kernels run on OpenBLAS (not the reference BLAS);
#   - numpy and scipy wheels from PyPI (they bundle their own OpenBLAS, scipy-openblas, which
#     ARPACK's dense work and the Python-side vector operations use), threadpoolctl (to print
#     which BLAS kernels run), and scikit-sparse 0.4.15 built against that CHOLMOD (0.5 needs
#     SuiteSparse 7).
# Idempotent: does nothing when DIR/bin/python already imports sksparse.cholmod.
set -euo pipefail
dir=${1:?usage: setup_eigsh_peer.sh VENV_DIR}
if [ -x "$dir/bin/python" ] && "$dir/bin/python" -c "import sksparse.cholmod, threadpoolctl" 2>/dev/null; then
    exit 0
fi
if ! dpkg -s libsuitesparse-dev libopenblas-dev >/dev/null 2>&1; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q libsuitesparse-dev libopenblas-dev
fi
arch=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || echo x86_64-linux-gnu)
for lib in libblas.so.3 liblapack.so.3; do
    update-alternatives --set "$lib-$arch" "/usr/lib/$arch/openblas-pthread/$lib" >/dev/null
done
python3 -m venv "$dir"
"$dir/bin/pip" install -q numpy scipy threadpoolctl cython
"$dir/bin/pip" install -q "scikit-sparse==0.4.15"
"$dir/bin/python" -c "import sksparse.cholmod" 
