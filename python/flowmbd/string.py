"""Travelling string (Ribaric ch. 4): the modes study of §4.2.3 (``flowmbd-string modes``) and
the speed sweep (``flowmbd-string sweep``), the pluck transient (``flowmbd-string
simulate``) and the string wrapped on two pulleys (``flowmbd-string wrap``). Series that the CLI writes as CSV files come back with ``series=True``: under the
CSV file's name without ``.csv``, a dict of its columns as numpy arrays."""

from __future__ import annotations

from typing import Any, Mapping, Optional

from . import _args, _native
from ._results import Result, config_json, from_json, with_series


def modes(
    speed: Optional[float] = 20.0,
    nodes: Optional[int] = 99,
    modes: Optional[int] = 40,
    config: Optional[Mapping[str, Any]] = None,
) -> Result:
    """Damped natural frequencies of the Galerkin model (4.29) and of the discrete
    flowing-material model (4.20) of the travelling string at one axial speed.

    Parameters
    ----------
    speed : axial speed [m/s] (replaces ``config["speed"]``; ``None`` keeps it).
    nodes : interior FE nodes, Ribaric (4.1) (``None`` keeps ``config["nodes"]``).
    modes : retained modes of the flowing model (``None`` keeps ``config["modes"]``, 20 by
        default in the CLI; this function's default is 40).
    config : dict with the keys of ``flowmbd-string modes --print-config``.

    Returns
    -------
    dict
        The CLI's ``summary.json``: ``speed``, ``critical_speed``, ``regime``
        (``"subcritical"``, ``"critical"`` or ``"supercritical"``), ``analytical_hz`` and
        ``flowing_hz`` (the models' neutral frequencies, numpy arrays), ``exact_hz`` (the
        closed form n|c² − v²|/(2cL) at every speed), ``unstable`` (true at the critical speed,
        divergence, and for growth that a second discretisation reproduces), the reproduced
        growth ``analytical_growth`` / ``flowing_growth`` and the truncation-dependent growth
        ``analytical_truncation_growth`` / ``flowing_truncation_growth`` (lists of dicts; above
        the critical speed every truncation has some, the string stays neutrally stable),
        ``growth_check``, the largest relative errors, ``warnings`` and ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        An eigen solve failed.
    """
    return from_json(
        _native.string_modes(
            config_json(config),
            _args.optional_number("speed", speed),
            _args.optional_count("nodes", nodes),
            _args.optional_count("modes", modes),
        )
    )



def sweep(
    config: Optional[Mapping[str, Any]] = None,
    nodes: Optional[int] = None,
    modes: Optional[int] = None,
    series: bool = False,
) -> Result:
    """Natural frequencies of the travelling string against the axial speed from 0 to
    ``max_speed_ratio`` times the critical speed ``c = sqrt(T/(rho A))``
    (``flowmbd-string sweep``): the neutral frequencies of the Galerkin model (4.29) and of
    the flowing-material model (4.20), and the exact ``f_n = n|c² − v²|/(2cL)``; every growing
    eigenvalue of a model is checked by a second discretisation (growth it does not reproduce
    is a truncation artefact; see :func:`modes`).

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-string sweep --print-config`` (``string``
        (``length`` [m], ``density`` [kg/m³], ``area`` [m²], ``tension`` [N]), ``nodes``,
        ``modes``, ``galerkin_terms``, ``max_speed_ratio``, ``steps``, ``tracked``,
        ``derivative``).
    nodes, modes : replace ``config["nodes"]`` and ``config["modes"]`` (the CLI's ``--nodes``,
        ``--modes``; ``None`` keeps them).
    series : also return ``"sweep"``: the columns of ``sweep.csv`` as numpy arrays
        (``speed_m_per_s`` [m/s]; ``analytical_f<n>_Hz``, ``flowing_f<n>_Hz``,
        ``exact_f<n>_Hz`` [Hz] for n = 1..tracked, NaN where a model has no such frequency;
        ``analytical_max_growth_1_per_s``, ``flowing_max_growth_1_per_s`` [1/s];
        ``string_unstable_flag``).

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``critical_speed`` [m/s], ``unstable_from``,
        ``analytical_truncation_growth_from``, ``flowing_truncation_growth_from`` [m/s] (or
        ``None``), ``max_rel_error_below_0_9c``, ``analytical_max_rel_error_above_1_1c`` and
        ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        An eigen solve failed.
    """
    text, data = _native.string_sweep(
        config_json(config),
        _args.optional_count("nodes", nodes),
        _args.optional_count("modes", modes),
    )
    return with_series(text, data, series)


def simulate(
    config: Optional[Mapping[str, Any]] = None,
    speed: Optional[float] = None,
    series: bool = False,
) -> Result:
    """The travelling string plucked into a triangle and let go (``flowmbd-string simulate``;
    Ribaric Fig. 4-6 right): the flowing-material model (4.20) integrated in time by RK4, the
    amplitude spectra of its modal coordinates and their peaks (the axial motion couples the
    modes, so each coordinate vibrates at several natural frequencies).

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-string simulate --print-config`` (``string``,
        ``speed`` [m/s], ``nodes``, ``modes``, ``pluck`` (``x`` [m], ``amplitude`` [m]),
        ``duration`` [s], ``step`` [s], ``sample_every``, ``peak_threshold``,
        ``derivative``). The speed must lie below the critical speed.
    speed : axial speed [m/s] (replaces ``config["speed"]``; the CLI's ``--speed``).
    series : also return ``"modal_history"`` (``t_s`` [s] and ``z<i>_sqrt_kg_m``, the modal
        coordinates of the mass-normalised modes [√kg·m]) and ``"spectra"`` (``f_Hz`` [Hz] and
        ``amp_z<i>_sqrt_kg_m``): the columns of ``modal_history.csv`` and ``spectra.csv`` as
        numpy arrays.

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``speed`` [m/s], ``model_hz`` (the model's natural
        frequencies) and ``exact_hz`` (n(c² − v²)/(2cL)) [Hz], ``resolution_hz`` [Hz],
        ``peaks`` (per mode its spectral peaks ``peaks_hz`` [Hz]), ``hamiltonian_drift`` (the
        relative drift of the energy-like invariant, a check of the integration) and
        ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message; also a step beyond RK4's stability
        limit, or a derivative operator whose model grows below the critical speed).
    flowmbd.NumericalError
        The response is not finite.
    """
    text, data = _native.string_simulate(config_json(config), _args.optional_number("speed", speed))
    return with_series(text, data, series)


def wrap(
    config: Optional[Mapping[str, Any]] = None,
    speed: Optional[float] = None,
    series: bool = False,
) -> Result:
    """The string partly wrapped on two pulleys, lifting off and landing again under a harmonic
    load (``flowmbd-string wrap``; Ribaric Fig. 4-4, 4-7, (4.10), (4.11), (4.31)–(4.40)):
    active-set Lagrange contact with event location, from the static wrap on the pulleys.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-string wrap --print-config`` (``string``
        (``length`` [m] anchor to anchor, ``density`` [kg/m³], ``area`` [m²], ``tension`` [N]),
        ``nodes``, ``pulleys`` (each ``center_x`` [m], ``top`` [m] above the anchors'
        line, ``radius`` [m]), ``candidate_half_width`` [m], ``formulation`` (``"nodal"`` or
        ``"craig_bampton"``), ``free_modes``, ``speed`` [m/s], ``load`` (``x`` [m],
        ``amplitude`` [N], ``frequency`` [Hz]), ``duration`` [s], ``sample`` [s],
        ``derivative``, ``contact`` (integrator tolerances), ``vtk_snapshots`` (unused here:
        no files are written)). The speed must lie below the critical speed.
    speed : axial speed [m/s] (replaces ``config["speed"]``; the CLI's ``--speed``).
    series : also return ``"history"`` (``t_s`` [s], ``midload_deflection_m`` [m],
        ``free_span_m`` [m], ``energy_J`` [J], per pulley ``pulley<p>_active_count`` and
        ``pulley<p>_force_N`` [N]) and ``"events"`` (``t_s`` [s], ``candidate_index``,
        ``node_index``, ``activated_flag`` (1 landing, 0 lift-off), ``impact_loss_J`` [J]): the
        columns of ``history.csv`` and ``events.csv`` as numpy arrays.

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``coordinates``, ``candidates_per_pulley``,
        ``initial_active_per_pulley``, ``initial_force_per_pulley`` [N] (the static wrap),
        ``min_active_per_pulley``, ``releases``, ``contacts``, ``impact_loss`` [J],
        ``max_free_span`` [m], ``max_active_gap`` [m] (constraint drift) and ``steps``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        The contact simulation failed.
    """
    text, data = _native.string_wrap(config_json(config), _args.optional_number("speed", speed))
    return with_series(text, data, series)
