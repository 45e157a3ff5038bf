"""Model reduction of sparse mass and stiffness matrices (Lin ch. 6), through the engine of
``flowmbd-reduce`` and the tire reduction. Matrices are scipy.sparse (any format) or dense
numpy arrays; results are numpy arrays. DOF indices are 0-based."""

from __future__ import annotations

from typing import Any, Optional, Sequence

import numpy as np
import scipy.sparse as sp

from . import _native


def _triplets(name: str, a: Any, n: Optional[int] = None):
    a = sp.coo_matrix(a)
    if a.shape[0] != a.shape[1]:
        raise ValueError(f"{name}: expected a square matrix, got {a.shape[0]}x{a.shape[1]}")
    if n is not None and a.shape[0] != n:
        raise ValueError(f"{name}: expected a {n}x{n} matrix, got {a.shape[0]}x{a.shape[1]}")
    return (
        a.shape[0],
        (
            np.ascontiguousarray(a.row, dtype=np.int64),
            np.ascontiguousarray(a.col, dtype=np.int64),
            np.ascontiguousarray(a.data, dtype=np.float64),
        ),
    )


def _dofs(name: str, dofs: Optional[Sequence[int]]) -> list:
    if dofs is None:
        return []
    out = []
    for d in np.asarray(dofs).ravel().tolist():
        if isinstance(d, bool) or int(d) != d or d < 0:
            raise ValueError(f"{name}: DOF {d} is not a non-negative integer")
        out.append(int(d))
    return out


def modes(M: Any, K: Any, count: int = 50, fixed: Optional[Sequence[int]] = None) -> dict:
    """The lowest ``count`` modes of ``K φ = λ M φ`` with the ``fixed`` DOFs clamped (sparse
    shift-invert Lanczos with a Sturm-sequence check; dense for small models).

    Returns ``{"eigenvalues": (count,) [rad²/s²], "frequencies_hz": (count,),
    "vectors": (n, count)}``: vectors M-normalised (``φᵀMφ = 1``), zero at the fixed DOFs,
    each signed so that its largest component is positive.

    Raises ``ValueError`` for bad input (shapes, DOF indices, non-finite entries).
    """
    n, m = _triplets("M", M)
    _, k = _triplets("K", K, n)
    if isinstance(count, bool) or int(count) != count or count < 0:
        raise ValueError(f"count: must be a non-negative integer, got {count}")
    values, hz, vectors = _native.modes(n, m, k, int(count), _dofs("fixed", fixed))
    return {
        "eigenvalues": np.asarray(values, dtype=float),
        "frequencies_hz": np.asarray(hz, dtype=float),
        "vectors": vectors,
    }


def craig_bampton(M: Any, K: Any, boundary: Sequence[int], modes: int) -> dict:
    """Craig–Bampton reduction (Lin (6.19)–(6.25)) keeping the ``boundary`` DOFs and
    ``modes`` fixed-interface modes (Lin (6.11)); ``modes = 0`` is Guyan's reduction (6.5).

    Returns ``{"M": (r, r), "K": (r, r), "basis": (n, r), "frequencies_hz": (r,)}`` with
    ``M_r = ΨᵀMΨ``, ``K_r = ΨᵀKΨ``; the columns of ``Ψ`` are the boundary DOFs (in the given
    order, ``Ψ = I`` on them), then the modes.

    Raises ``ValueError`` for bad input (shapes, repeated or out-of-range DOFs, a singular
    ``K_ii``).
    """
    n, m = _triplets("M", M)
    _, k = _triplets("K", K, n)
    if isinstance(modes, bool) or int(modes) != modes or modes < 0:
        raise ValueError(f"modes: must be a non-negative integer, got {modes}")
    mr, kr, psi, hz = _native.craig_bampton(n, m, k, _dofs("boundary", boundary), int(modes))
    return {"M": mr, "K": kr, "basis": psi, "frequencies_hz": hz}
