"""Type stub of the native module ``flowmbd._native`` (Rust, pyo3). Use the public wrappers in
:mod:`flowmbd.belt`, :mod:`flowmbd.string` and :mod:`flowmbd.reduce` instead."""

from typing import List, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

_Triplets = Tuple[npt.NDArray[np.int64], npt.NDArray[np.int64], npt.NDArray[np.float64]]

def speed_loss(
    config: Optional[str] = None,
    omega: Optional[float] = None,
    torques: Optional[Sequence[float]] = None,
    model: Optional[str] = None,
) -> str:
    """JSON text of the speed-loss summary (``summary.json`` of ``flowmbd-belt speed-loss``)."""

def ancf(config: Optional[str] = None, t_end: Optional[float] = None) -> str:
    """JSON text of the ANCF belt-drive summary (``summary.json`` of ``flowmbd-belt ancf``)."""

def plate(config: Optional[str] = None, t_end: Optional[float] = None) -> str:
    """JSON text of the plate-belt summary (``summary.json`` of ``flowmbd-belt plate``)."""

def string_modes(
    config: Optional[str] = None,
    speed: Optional[float] = None,
    nodes: Optional[int] = None,
    modes: Optional[int] = None,
) -> str:
    """JSON text of the string modes summary (``summary.json`` of ``flowmbd-string modes``)."""

def modes(
    n: int, m: _Triplets, k: _Triplets, count: int, fixed: List[int]
) -> Tuple[List[float], List[float], npt.NDArray[np.float64]]:
    """(eigenvalues, frequencies [Hz], n × count vectors) of the clamped model."""

def craig_bampton(
    n: int, m: _Triplets, k: _Triplets, boundary: List[int], n_modes: int
) -> Tuple[
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
]:
    """(M_r, K_r, Ψ, frequencies [Hz]) of the Craig–Bampton reduction."""
