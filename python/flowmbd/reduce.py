"""Model reduction of sparse mass and stiffness matrices (Lin ch. 6), through the engine of
``flowmbd-reduce`` and the tire reduction. Matrices are scipy.sparse (any format) or dense
numpy arrays; results are numpy arrays. DOF indices are 0-based."""

from __future__ import annotations

from typing import Any, Optional, Sequence

import numpy as np
import scipy.sparse as sp

from . import _args, _native


def _triplets(name: str, a: Any, n: Optional[int] = None):
    if isinstance(a, (str, bytes, bool)) or a is None:
        raise ValueError(f"{name}: expected a matrix (scipy.sparse or numpy), got {type(a).__name__}")
    try:
        a = sp.coo_matrix(a)
        if a.ndim != 2 or not np.issubdtype(a.dtype, np.number) or np.iscomplexobj(a.data):
            raise ValueError("not a real matrix")
    except (TypeError, ValueError, OverflowError, RecursionError) as e:
        raise ValueError(f"{name}: expected a real matrix (scipy.sparse or numpy): {e}") from e
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
    if isinstance(dofs, (str, bytes)):
        raise ValueError(f"{name}: expected a list of DOF indices, got a string")
    try:
        items = np.asarray(dofs, dtype=object).ravel().tolist()
    except (TypeError, ValueError, OverflowError, RecursionError) as e:
        raise ValueError(f"{name}: expected a list of DOF indices ({e})") from e
    return [_args.count(f"{name}[{i}]", d) for i, d in enumerate(items)]


def modes(M: Any, K: Any, count: int = 50, fixed: Optional[Sequence[int]] = None) -> dict:
    """The lowest ``count`` modes of ``K φ = λ M φ`` with the ``fixed`` DOFs clamped (sparse
    shift-invert Lanczos with a Sturm-sequence check; dense for small models).

    Returns ``{"eigenvalues": (count,) [rad²/s²], "frequencies_hz": (count,),
    "vectors": (n, count)}``: vectors M-normalised (``φᵀMφ = 1``), zero at the fixed DOFs,
    each signed so that its largest component is positive.

    Raises ``ValueError`` for bad input (shapes, DOF indices, non-finite entries, a
    non-symmetric matrix, more modes than the model has free DOFs).
    """
    n, m = _triplets("M", M)
    _, k = _triplets("K", K, n)
    count = _args.count("count", count)
    values, hz, vectors = _native.modes(n, m, k, count, _dofs("fixed", fixed))
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

    Raises ``ValueError`` for bad input (shapes, repeated or out-of-range DOFs, a
    non-symmetric matrix, a singular ``K_ii``).
    """
    n, m = _triplets("M", M)
    _, k = _triplets("K", K, n)
    modes = _args.count("modes", modes)
    mr, kr, psi, hz = _native.craig_bampton(n, m, k, _dofs("boundary", boundary), modes)
    return {"M": mr, "K": kr, "basis": psi, "frequencies_hz": hz}


def eitelberg(M: Any, K: Any, boundary: Sequence[int], fixed: Sequence[int] = ()) -> dict:
    """Eitelberg's equation-error reduction (Lin §6.6, Appendix C) of the structure
    ``M δ̈ + K δ = f`` onto the ``boundary`` DOFs, the ``fixed`` DOFs clamped first (Lin
    (6.42)–(6.45), with the stabilising output feedback removed afterwards); the CLI's
    ``flowmbd-reduce reduce --method eitelberg``. Dense: at most 1000 unclamped DOFs.

    Returns ``{"minv_k": (b, b), "A": (2b, 2b), "B": (2b, b), "C": (2b, 2b),
    "frequencies_hz": (b,)}``: ``M_⁻¹K_`` on the boundary DOFs [1/s²] (Lin §6.6.4's printed
    matrix; it equals Guyan's ``M_g⁻¹K_g``), the reduced state-space system of
    ``ξ = {δ_b; δ̇_b}`` and the natural frequencies ``√λ/2π`` of ``M_⁻¹K_``, ascending.

    Raises ``ValueError`` for bad input (shapes, repeated or out-of-range DOFs, a
    non-symmetric matrix, too many DOFs).
    """
    n, m = _triplets("M", M)
    _, k = _triplets("K", K, n)
    minv_k, a, b, c, hz = _native.eitelberg(
        n, m, k, _dofs("boundary", boundary), _dofs("fixed", fixed)
    )
    return {"minv_k": minv_k, "A": a, "B": b, "C": c, "frequencies_hz": hz}
