"""Model reduction of sparse mass and stiffness matrices (Lin ch. 6), through the engine of
``flowmbd-reduce`` and the tire reduction. Matrices are scipy.sparse (any format) or dense
numpy arrays; results are numpy arrays. DOF indices are 0-based. The studies ``lin_beam``,
``lin_slab`` (Lin's Appendix A beam and Appendix B slab) and ``tire_mesh`` (the generated
tire's K and M) are those of ``flowmbd-reduce``."""

from __future__ import annotations

from typing import Any, Mapping, Optional, Sequence

import numpy as np
import scipy.sparse as sp

from . import _args, _native
from ._results import Result, config_json, from_json, with_series


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


def lin_beam(config: Optional[Mapping[str, Any]] = None, series: bool = False) -> Result:
    """Lin ch. 6.2, 6.3, 7.1 and 8.5 on the Appendix A beam (``flowmbd-reduce lin-beam``):
    frequencies of the full five-node beam and of its reduced models, the profile tests of
    §7.1 and the mean-axes eigenproblem (8.45) with mode condensation.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-reduce lin-beam --print-config``: ``beam``
        (``young_modulus_pa`` [Pa], ``area_m2`` [m²], ``second_moment_m4`` [m⁴], ``length_m``
        [m], ``node_masses_kg`` [kg], 5 values) and ``profile_delta_m`` (the assumed
        deformation (7.1), DOF order ξ1, η1, …, ξ5, η5 [m]); default Lin's Appendix A.
    series : also return ``"profiles"`` (``dof_index``, ``reference_m`` and the deflections
        ``p<1|2>_<mt|cb|mc>_m`` [m] of profiles 1 and 2 with modal truncation, Craig–Bampton
        and mode condensation) and ``"frequencies"`` (``set_index``: 0 free-free, 1 Guyan (a),
        2 Guyan (b), 3 fixed-interface, 4 mean-axes; ``mode_index``; ``frequency_Hz`` [Hz]):
        the columns of ``profiles.csv`` and ``frequencies.csv``.

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``free_free_hz``, ``guyan_a_hz`` (masters 1, 3, 5),
        ``guyan_b_hz`` (masters 1, 2, 5), ``fixed_interface_hz`` (boundary nodes 1, 5),
        ``mean_axes_normal_hz`` [Hz], ``profile1_errors`` and ``profile2_errors`` (‖δ* − δ‖
        [m] of MT, CB, MC) and ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message, e.g. ``beam.length_m: …``).
    flowmbd.NumericalError
        An eigen solve or reduction failed.
    """
    text, data = _native.lin_beam(config_json(config))
    return with_series(text, data, series)


def lin_slab(config: Optional[Mapping[str, Any]] = None, series: bool = False) -> Result:
    """Lin §7.2 simulations 1–3 on the Appendix B slab (``flowmbd-reduce lin-slab``): the local
    deflection δ'8 of node 8 in the floating frame with no reduction (NR), Guyan (GR),
    fixed-interface modal truncation (MT), Craig–Bampton (CB) and mode condensation (MC).
    Simulation 3 first regenerates Lin's acceleration tables with the previous simulation of
    Fig. 7-12(b).

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-reduce lin-slab --print-config``:
        ``simulations`` (``"no-rigid-motion"``, ``"orbit"``, ``"emulated"``), ``methods``
        (``"no-reduction"`` (required: the reference), ``"guyan"``,
        ``"fixed-interface-modal-truncation"``, ``"craig-bampton"``, ``"mode-condensation"``)
        and ``params`` (``duration_s`` [s], ``step_s`` [s], ``n_modes``, ``orbit_radius_m``
        [m], ``orbit_period_s`` [s], ``sim3``); default all three simulations, all methods,
        1 s with RK4 steps of 1 ms.
    series : also return ``"<sim>_node8"`` per simulation (``t_s`` [s], then
        ``<method>_xi_m``, ``<method>_eta_m``, ``<method>_zeta_m`` [m]) and, with simulation
        3, ``"sim3_tables"`` (``t_s``, ``a<x|y|z><node>_m_per_s2`` [m/s²] of nodes 16, 18, 28,
        30) and ``"sim3_source_node8"`` (``t_s``, ``xi_m``, ``eta_m``, ``zeta_m`` [m]): the
        columns of the CSV files of those names.

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``sim1_statics_m`` (δ'8 of the gravity statics per method
        [m]), ``simulations`` (per simulation and method ``rms_vs_nr_m``, ``peak_m``,
        ``max_drift_m`` [m]), ``cb_mc_max_difference_m`` [m] (Lin §6.5.4: zero up to
        round-off), ``sim3_source`` and ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message, e.g. ``methods: …``).
    flowmbd.NumericalError
        A model or simulation failed (the statics computed so far attached as ``partial``).
    """
    text, data = _native.lin_slab(config_json(config))
    return with_series(text, data, series)


def _sparse(n: int, triplets) -> sp.csc_matrix:
    rows, cols, vals = triplets
    return sp.csc_matrix((vals, (rows.astype(np.int64), cols.astype(np.int64))), shape=(n, n))


def tire_mesh(config: Optional[Mapping[str, Any]] = None) -> Result:
    """The generated truck-tire carcass with its stiffness and mass matrices on all DOFs
    (``flowmbd-reduce tire-mesh``): fe-model's generator (295/80 R22.5 at 38 psi by default,
    63 936 DOFs standing in for Ribaric §8.1's ABAQUS model). Unlike
    :func:`flowmbd.tire.generate` (always the lumped mass of the reduction, Ribaric §7.2), the
    mass is consistent by default and every node set is returned.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-reduce tire-mesh --print-config``: ``tire`` (the
        generator, the keys of ``[tire.generator]``), ``mass`` (``"consistent"`` or
        ``"lumped"``) and ``geometric_stiffness`` (add the inflation prestress to ``K``,
        default true).

    Returns
    -------
    Result
        The CLI's ``summary.json`` without ``files``: ``nodes``, ``elements``, ``dof``,
        ``nnz_k``, ``node_sets`` (set sizes), ``mass_kg`` (total mass [kg]) and ``meaning``;
        and what the CLI writes as files: ``"K"`` [N/m] and ``"M"`` [kg] (scipy.sparse CSC,
        3n × 3n, node-major DOFs x, y, z; ``K.mtx``, ``M.mtx``), ``"coordinates"`` (n × 3
        node positions [m], wheel frame; ``mesh.json``) and ``"node_set_nodes"`` (``{name:
        0-based node indices}``; ``node_sets.json``, e.g. ``"rim"`` and ``"contact_patch"``).

    Raises
    ------
    ValueError
        Bad input (the CLI's ``tire.…: reason`` message).
    flowmbd.NumericalError
        The assembly failed.
    """
    text, nodes, k, m, sets = _native.tire_mesh(config_json(config))
    out = from_json(text)
    n = 3 * nodes.shape[0]
    out["K"] = _sparse(n, k)
    out["M"] = _sparse(n, m)
    out["coordinates"] = nodes
    out["node_set_nodes"] = {name: ids.astype(np.int64) for name, ids in sets.items()}
    return out
