"""Type stub of the native module ``flowmbd._native`` (Rust, pyo3). Use the public wrappers in
:mod:`flowmbd.belt`, :mod:`flowmbd.beam`, :mod:`flowmbd.string`, :mod:`flowmbd.tire` and
:mod:`flowmbd.reduce` instead (``ReducedTire`` is public as ``flowmbd.tire.ReducedTire``)."""

import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

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

def fead(config: Optional[str] = None, rpm: Optional[List[float]] = None) -> str:
    """JSON text of the FEAD sweep summary (``summary.json`` of ``flowmbd-belt fead``)."""

def string_modes(
    config: Optional[str] = None,
    speed: Optional[float] = None,
    nodes: Optional[int] = None,
    modes: Optional[int] = None,
) -> str:
    """JSON text of the string modes summary (``summary.json`` of ``flowmbd-string modes``)."""

def string_sweep(
    config: Optional[str] = None,
    nodes: Optional[int] = None,
    modes: Optional[int] = None,
) -> Tuple[str, dict]:
    """(JSON text of the string sweep summary, ``{"sweep": {column: array}}``)."""

def wave(
    config: Optional[str] = None, speed: Optional[float] = None, t_end: Optional[float] = None
) -> Tuple[str, dict]:
    """(JSON text of the travelling-wave demonstration's summary, ``{"wave": {column:
    array}}``)."""

def demo(
    config: Optional[str] = None, t_end: Optional[float] = None
) -> Tuple[str, dict]:
    """(JSON text of the slider-crank demonstration's summary, ``{"history": {column:
    array}}``)."""

def string_simulate(
    config: Optional[str] = None, speed: Optional[float] = None
) -> Tuple[str, dict]:
    """(JSON text of the pluck-transient summary, ``{"modal_history", "spectra": {column:
    array}}``)."""

def string_wrap(
    config: Optional[str] = None, speed: Optional[float] = None
) -> Tuple[str, dict]:
    """(JSON text of the wrapped string's summary, ``{"history", "events": {column:
    array}}``)."""

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

def eitelberg(
    n: int, m: _Triplets, k: _Triplets, boundary: List[int], fixed: List[int]
) -> Tuple[
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
]:
    """(M⁻¹K on the boundary, A_r, B_r, C_r, frequencies [Hz]) of Eitelberg's reduction."""

def lin_beam(config: Optional[str] = None) -> Tuple[str, dict]:
    """(JSON text of the ``flowmbd-reduce lin-beam`` summary, ``{"profiles", "frequencies":
    {column: array}}``)."""

def lin_slab(config: Optional[str] = None) -> Tuple[str, dict]:
    """(JSON text of the ``flowmbd-reduce lin-slab`` summary, ``{"<sim>_node8",
    "sim3_tables", "sim3_source_node8": {column: array}}``)."""

def tire_mesh(
    config: Optional[str] = None,
) -> Tuple[
    str,
    npt.NDArray[np.float64],
    Tuple[npt.NDArray[np.uintp], npt.NDArray[np.uintp], npt.NDArray[np.float64]],
    Tuple[npt.NDArray[np.uintp], npt.NDArray[np.uintp], npt.NDArray[np.float64]],
    dict,
]:
    """(JSON text of the ``flowmbd-reduce tire-mesh`` summary without ``files``, nodes (n × 3),
    K triplets, M triplets, ``{node set: node indices}``)."""

def beam_simply_supported(
    config: Optional[str] = None,
    element: Optional[str] = None,
    nu: Optional[float] = None,
    elements: Optional[int] = None,
) -> str:
    """JSON text of the ``flowmbd-beam simply-supported`` summary."""

def beam_cantilever(
    config: Optional[str] = None,
    element: Optional[str] = None,
    h: Optional[float] = None,
    nu: Optional[float] = None,
    elements: Optional[int] = None,
) -> Tuple[str, dict]:
    """(JSON text of the ``flowmbd-beam cantilever`` summary, ``{"shape": {column: array}}``)."""

def beam_pendulum(
    config: Optional[str] = None, elements: Optional[int] = None
) -> Tuple[str, dict]:
    """(JSON text of the ``flowmbd-beam pendulum`` summary, ``{"history": {column: array}}``)."""

def beam_spinning(
    config: Optional[str] = None, elements: Optional[int] = None
) -> Tuple[str, dict]:
    """(JSON text of the ``flowmbd-beam spinning`` summary, ``{"history": {column: array}}``)."""

def beam_ground_contact(
    config: Optional[str] = None,
    element: Optional[str] = None,
    elements: Optional[int] = None,
    load_factor: Optional[float] = None,
) -> Tuple[str, dict]:
    """(JSON text of the ``flowmbd-beam ground-contact`` summary, ``{"contact": {column:
    array}}``)."""

_Array = npt.NDArray[np.float64]
_Index = npt.NDArray[np.uintp]
_Fe = Tuple[_Array, Tuple[_Index, _Index, _Array], _Array, _Index, _Index]

CLEAT_FORCE_COLUMNS: List[str]
"""Columns of the cleat test's force history (``forces.csv``)."""

CLEAT_SPECTRUM_COLUMNS: List[str]
"""Columns of the cleat test's amplitude spectra (``spectra.csv``)."""

class BeltSimulation:
    """A belt drive stepped in time (``drives::AnySimulation``); public as
    ``flowmbd.belt.Simulation``."""

    model: str
    step_size: float
    t: float
    q: npt.NDArray[np.float64]
    v: npt.NDArray[np.float64]
    coordinate_names: List[str]
    pulley_speeds: npt.NDArray[np.float64]
    belt_speed: float
    arm_angle: Optional[float]
    def __init__(self, config: Optional[str] = None) -> None: ...
    def step(self, n: int = 1) -> None: ...
    def run_to(self, t_end: float) -> None: ...
    def set_state(
        self, t: float, q: npt.NDArray[np.float64], v: npt.NDArray[np.float64]
    ) -> None: ...
    def set_signal(self, k: int, signal: str) -> None: ...
    def report(self) -> str: ...

class ReducedTire:
    """The reduced flowing-material tire of Ribaric §8.2 (immutable, picklable)."""

    m: _Array
    """``M_z = TᵀMT`` [kg] (n_z × n_z)."""
    k: _Array
    """``K_z = TᵀKT`` [N/m]."""
    g1: _Array
    """``G₁ = TᵀMT_,θ`` [kg/rad]."""
    g2: _Array
    """``G₂ = TᵀMT_,θθ`` [kg/rad²]."""
    k1: _Array
    """``K₁ = TᵀKT_,θ`` [N/(m rad)]."""
    kr: _Array
    """Rim force per coordinate (3 × n_z) [N/m], Ribaric (7.2)."""
    kr1: _Array
    kt: _Array
    """Rim moment per coordinate (3 × n_z) [N], Ribaric (7.2)."""
    kt1: _Array
    tc: _Array
    """Contact-node rows of ``T`` (3 n_c × n_z)."""
    tc_theta: _Array
    """Contact-node rows of ``T_,θ`` (3 n_c × n_z) [1/rad]."""
    p_e: _Array
    """Translational momentum per coordinate ``eᵀMT`` (3 × n_z) [kg]."""
    p_e1: _Array
    p_e2: _Array
    m_theta: _Array
    """``m_θ = TᵀM s_,θ`` [kg m/rad]."""
    c_s: _Array
    """``c_s = TᵀM s_,θθ`` [kg m/rad²]."""
    n_free_modes: int
    n_contact: int
    n_z: int
    dof: int
    """Wheel–tire DOF ``6 + n_z``."""
    contact_nodes: _Index
    contact_positions: _Array
    """Undeformed contact-node positions (n_c × 3) [m]."""
    free_mode_hz: _Array
    contact_mode_hz: _Array
    tire_mass: float
    """[kg] without the rim nodes."""
    rim_mass: float
    rim_spin_inertia: float
    outer_radius: float
    source: str
    """What the tire was made from (generator, or the imported files' SHA-256 digests, and the
    reduction, JSON)."""
    code_version: str
    """The version of the code that reduced it (package version and source digest)."""
    def frequencies_hz(self) -> _Array:
        """Eigenfrequencies of the reduced tire, wheel fixed, not rolling [Hz]."""
    def to_json(self) -> str:
        """The versioned JSON text (the ``flowmbd-tire reduce`` file)."""
    @staticmethod
    def from_json(text: str) -> "ReducedTire": ...
    def save(self, path: Union[str, os.PathLike]) -> None: ...
    @staticmethod
    def load(path: Union[str, os.PathLike]) -> "ReducedTire":
        """A saved reduced tire: a regular file of at most 1 GiB whose checksum holds
        (``ValueError`` otherwise)."""
    def __reduce__(self) -> tuple: ...

def tire_generate(config: Optional[str] = None) -> _Fe:
    """(nodes, K triplets, lumped mass per DOF, rim nodes, patch nodes) of the generated tire."""

def tire_import(config: str) -> _Fe:
    """The same for the imported tire (``[tire.import]`` as JSON text)."""

def tire_reduce(config: Optional[str] = None) -> ReducedTire:
    """The reduced tire of the ``[tire]`` table (JSON text)."""

def tire_steady(
    config: Optional[str] = None, tire: Optional[ReducedTire] = None
) -> Tuple[str, Optional[str]]:
    """JSON text of the steady-state study's summary (``flowmbd-tire steady``) and the MF 6.1
    ``.tir`` text of its Magic Formula fit (``None`` without a fit)."""

def tire_cleat(
    config: Optional[str] = None,
    speed_kmh: Optional[float] = None,
    tire: Optional[ReducedTire] = None,
) -> Tuple[str, List[List[float]], List[List[float]]]:
    """(JSON text of the cleat summary, force history columns, spectra columns)."""

def tire_rotating_modes(
    config: Optional[str] = None,
    speeds_kmh: Optional[List[float]] = None,
    tire: Optional[ReducedTire] = None,
) -> Tuple[str, dict]:
    """(JSON text of the rotating-modes summary, ``{"rotating_modes": {column: array}}``)."""

def tire_sweep(
    config: Optional[str] = None,
    speeds_kmh: Optional[List[float]] = None,
    tire: Optional[ReducedTire] = None,
) -> Tuple[str, dict]:
    """(JSON text of the sweep summary, the series: ``waterfall``, ``spectrum_map``,
    ``run_series``)."""

def tire_dips(
    config: Optional[str] = None, tire: Optional[ReducedTire] = None
) -> Tuple[str, dict]:
    """(JSON text of the dips summary, ``{"profile_<ground>", "prediction_<ground>",
    "sweep_<ground>": {column: array}}``)."""

def tire_pressure(
    config: Optional[str] = None, tire: Optional[ReducedTire] = None
) -> Tuple[str, dict]:
    """(JSON text of the pressure summary, ``{"patch_drum", "patch_road": {column: array}}``)."""

def tire_modes(config: Optional[str] = None) -> Tuple[str, dict]:
    """(JSON text of the modes summary, ``{"modes", "loaded_modes": {column: array}}``)."""

class TireSimulation:
    """The reduced tire rolling on the cleat rig, stepped in time; public as
    ``flowmbd.tire.Simulation``."""

    t: float
    settle_time: float
    step_size: float
    spin: float
    drive_torque: float
    coordinates: npt.NDArray[np.float64]
    normal_forces: npt.NDArray[np.float64]
    contact_positions: npt.NDArray[np.float64]
    def __init__(self, config: Optional[str] = None, tire: Optional[ReducedTire] = None) -> None: ...
    prescribed_spin: Optional[float]
    reaction_torque: float
    spin_torque: float
    def prescribe_spin(self, rate: Optional[float] = None) -> None: ...
    def forces(self) -> Dict[str, float]: ...
    def state(self) -> Dict[str, Any]: ...
    def set_state(self, state: Dict[str, Any]) -> None: ...
    def step(self, n: int) -> None: ...
    def run_to(self, t_end: float) -> None: ...

class TireCoSimulation:
    """The rolling tire driven by its wheel-centre motion (``tire::motion::CoSimulation``, the
    FMU's model); public as ``flowmbd.tire.CoSimulation``."""

    t: float
    def __init__(
        self,
        config: Optional[str] = None,
        tire: Optional[ReducedTire] = None,
        motion: Optional[str] = None,
    ) -> None: ...
    def motion(self) -> Dict[str, Any]: ...
    def do_step(self, h: float, motion: str) -> Dict[str, float]: ...

def tire_build_fmu(
    out: Union[str, os.PathLike],
    library: Union[str, os.PathLike],
    config: Optional[str] = None,
    tire: Optional[ReducedTire] = None,
) -> Dict[str, Any]:
    """Write the FMI 3.0 co-simulation FMU of the tire (JSON text of a cleat-study dict) to
    ``out`` with the compiled library ``library`` packed; returns the start motion."""
