"""Belt drives: the speed-loss study of Ribaric §6.4–6.5 (``flowmbd-belt speed-loss``), the
planar ANCF drive of Kerkkänen ch. 3 (``flowmbd-belt ancf``) and his three-dimensional plate-belt
drive of ch. 4 (``flowmbd-belt plate``), the FEAD sweep (``flowmbd-belt fead``) and its steady
design without time stepping (``flowmbd-belt design``), the travelling span wave
(``flowmbd-belt wave``) and the slider-crank demonstration (``flowmbd-belt demo``)."""

from __future__ import annotations

from typing import Any, Mapping, Optional, Sequence

from . import _args, _native
from ._stepping import Native, Stepping
from ._results import Result, config_json, from_json, with_series


def speed_loss(
    omega: Optional[float] = 62.8,
    torques: Optional[Sequence[float]] = (0.0, 10.0),
    model: Optional[str] = "flowing",
    config: Optional[Mapping[str, Any]] = None,
) -> Result:
    """Angular speed loss ``Δω = ω₁ − ω₂`` against the load torque (Ribaric Figs. 6-6, 6-7),
    with Bechtel's analytical line (6.3).

    Parameters
    ----------
    omega : driver speed [rad/s]; replaces ``config["omegas"]`` (``None`` keeps the
        configured list, by default ``[62.8, 22.6]``).
    torques : load torques [N m]; replace ``config["procedure"]["torques"]`` (``None`` keeps them).
    model : ``"flowing"`` (Ribaric (5.14)), ``"nodal"`` ((5.7)) or ``"ancf"`` (Kerkkänen ch. 3);
        ``None`` keeps ``config["model"]``.
    config : the study configuration as a dict with the keys of the TOML file
        (``flowmbd-belt speed-loss --print-config``); missing keys keep their defaults.

    Returns
    -------
    dict
        The content of the CLI's ``summary.json`` (``omega_driver``, ``model``, ``points``,
        ``analytical`` (array), ``cases``, ``modal_coordinates``, ``wall_time_s``). Each point
        holds ``torque`` [N m], ``delta_omega`` [rad/s], ``tension_tight`` and
        ``tension_slack`` [N], ``gross_slip`` (bool) with ``gross_slip_at`` (pulley, time,
        criterion), ``slip_arc_driver_rad`` and ``slip_arc_driven_rad``, ``hub_loads`` (list of
        ``{"name", "force", "magnitude"}`` [N]), ``pulleys`` (arcs, slip velocities, hub load,
        torque, sliding loss per pulley), ``spans`` (tension and transverse vibration
        amplitude per span), and ``linearisation_valid`` / ``linearisation``: for the flowing
        and nodal models, linearised about the pre-tension, the numbers are ``None`` where the
        slack span goes nearly slack or a wrap slides as a whole; ``caveat``: why the speed
        loss may understate the creep (the flowing model's default contact rates under a
        friction law sharper than the creep), or ``None``; ``balances`` (torque and power
        residuals) and ``balance``: what they say when either misses 0.5 %, or ``None``. Each
        case adds
        ``capacity_euler_eytelwein`` [N m]. A load beyond what friction can transmit is a point
        with ``gross_slip = True``, not an error.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        The integration failed; ``err.partial`` holds the points found so far.
    """
    return from_json(
        _native.speed_loss(
            config_json(config),
            _args.optional_number("omega", omega),
            _args.optional_numbers("torques", torques),
            model,
        )
    )


def ancf(config: Optional[Mapping[str, Any]] = None, t_end: Optional[float] = None) -> Result:
    """The planar ANCF belt drive of Kerkkänen ch. 3 (``flowmbd-belt ancf``): by default
    example 3.3-B (Table 3.1, 20 elements, driver ramp (3.29) to 12 rad/s, 1 s);
    ``config={"analysis": "static_closure"}`` is example 3.3-A.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-belt ancf --print-config`` (``analysis``,
        ``t_end``, ``tangent_refresh``, ``drive``, ``integrator``, ``output``).
    t_end : end time [s] (replaces ``config["t_end"]``; the CLI's ``--t-end``).

    Returns
    -------
    dict
        The CLI's ``summary.json``: end speeds of driver and driven pulley [rad/s], tight and
        slack span tensions [N], ``speed_ratio``, ``initial_tension``, ``steps``,
        ``newton_iterations``, ``t_end``, ``wall_time_s``; for a dynamic run also
        ``gross_slip``, ``slip_arc_driver_rad``, ``slip_arc_driven_rad``, ``hub_loads``,
        ``pulleys`` and ``spans`` at the end (closure: ``closure_radius`` and
        ``closure_radius_variation``).

    Raises
    ------
    ValueError
        Bad input (the CLI's message).
    flowmbd.NumericalError
        The integration failed; ``err.partial`` is the summary at the state reached.
    """
    return from_json(_native.ancf(config_json(config), _args.optional_number("t_end", t_end)))


def plate(config: Optional[Mapping[str, Any]] = None, t_end: Optional[float] = None) -> Result:
    """The three-dimensional plate-belt drive of Kerkkänen ch. 4 (``flowmbd-belt plate``): by
    default Model 2 of Table 4.1 (20 thin-plate elements, driver ramp (3.29) to 500 rad/s, load
    (4.47) to 2 N m, 1.3 s; about 10 min on a free core), compared with Bechtel's steady
    analytical model; ``config`` with the keys of ``apps/belt/examples/kerkkanen-4-6-model1.toml``
    gives Model 1.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-belt plate --print-config`` (``t_end``, ``drive``,
        ``integrator``, ``output``).
    t_end : end time [s] (replaces ``config["t_end"]``; the CLI's ``--t-end``).

    Returns
    -------
    dict
        The CLI's ``summary.json``: ``omega_driver_end``, ``omega_driven_end`` and the window
        means [rad/s], ``analytical_omega_driven`` and ``capstan_omega_driven`` [rad/s],
        ``tension_tight``, ``tension_slack`` (strain (4.9)) and ``span_tensions`` by the three
        strain measures [N], ``contact_torque_driven``, ``tension_torque``, ``membrane_torque``
        [N m], ``steps``, ``newton_iterations``, ``t_end``, ``wall_time_s``; and the drive at
        the end as every belt model reports it (the same keys as :func:`ancf`):
        ``gross_slip``, ``slip_arc_driver_rad``, ``slip_arc_driven_rad``, ``hub_loads``,
        ``pulleys`` and ``spans`` (span forces: the membrane forces).

    Raises
    ------
    ValueError
        Bad input (the CLI's message).
    flowmbd.NumericalError
        The integration failed; ``err.partial`` is the summary at the state reached.
    """
    return from_json(_native.plate(config_json(config), _args.optional_number("t_end", t_end)))


def fead(config: Optional[Mapping[str, Any]] = None, rpm: Optional[Sequence[float]] = None) -> Result:
    """The front-end accessory drive sweep (``flowmbd-belt fead``): a six-pulley passenger-car
    drive with an automatic tensioner, run over engine speeds with the crank's firing-order speed
    fluctuation and the accessory loads, on the flowing-material belt model (``model``:
    ``"flowing"``, ``"nodal"`` or ``"ancf"``, the slow reference).

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-belt fead --print-config`` (``drive``, ``engine``,
        ``run``, ``model``, ``ancf``).
    rpm : engine speeds [rpm] (replaces ``config["engine"]["speeds_rpm"]``; the CLI's ``--rpm``).

    Returns
    -------
    dict
        The CLI's ``summary.json``: installed tension [N], belt length [m], the tensioner's static
        arm angle [rad], wrap angles [deg], and per engine speed the arm angle range, span
        tension extremes, speed loss per pulley, the drive report and the spans' transverse
        frequencies [Hz].

    Raises
    ------
    ValueError
        Bad input (the CLI's message).
    flowmbd.NumericalError
        The sweep failed; ``err.partial`` holds the engine speeds completed.
    """
    speeds = _args.optional_numbers("rpm", rpm)
    return from_json(_native.fead(config_json(config), speeds))


def design(config: Optional[Mapping[str, Any]] = None, rpm: Optional[Sequence[float]] = None) -> Result:
    """The steady FEAD design without time stepping (``flowmbd-belt design``, issue 36): per
    engine speed the span tensions [N] (centrifugal tension included), the tensioner arm's angle
    and force, each wrap's adhesion and slip arcs (creep theory), hub loads [N] and slip margins,
    the drive's rotational modes (the belt held on the adhesion arcs, the slip arcs stretching:
    ``design.wrap = "creep"``, the default; ``"held"`` holds the whole wrap, whose frequencies
    every point also reports as ``held_wrap_frequencies_hz``), the spans' transverse modes and
    the coupled modes (spans,
    pulleys and tensioner arm together: ``coupled_modes`` with ``coupled_parts``) [Hz], the
    Campbell diagram with its crossings, and the findings (warnings and errors before any time stepping).

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-belt design --print-config`` (``drive``,
        ``engine``, ``design``).
    rpm : engine speeds [rpm] (replaces ``config["engine"]["speeds_rpm"]``; the CLI's ``--rpm``).

    Returns
    -------
    dict
        The CLI's ``summary.json``; ``layout`` and ``meaning`` name the drive it ran.

    Raises
    ------
    ValueError
        Bad input (the CLI's message).
    """
    speeds = _args.optional_numbers("rpm", rpm)
    return from_json(_native.design(config_json(config), speeds))


class Simulation(Stepping):
    """A belt drive stepped in time: build the model from a layout, step it, read and set its
    state, change a pulley's speed or load between steps, observe it, and read the report of
    any state (the same model, generalized-α stepper and report as the studies; Rust:
    ``drives::AnySimulation``).

    Parameters
    ----------
    config : dict with the keys ``model`` (``"flowing"``, ``"nodal"`` or ``"ancf"``),
        ``drive`` (a layout, as in ``flowmbd-belt fead --print-config``: ``pulleys`` with their
        ``motion``, ``tensioner``, ``belt``, ``tension``, ``contact``, ``damping``), ``step``
        [s] and ``models`` (each model's discretisation); missing keys keep their defaults:
        Ribaric's Table 6-1 drive, the driver ramped to 62.8 rad/s in 0.3 s, then the driven
        pulley's load ramped to 10 N m in 0.1 s, the flowing model, a step of 0.25 ms.

    Raises
    ------
    ValueError
        Bad input (the message names the field, e.g. ``drive.pulleys[1].radius``).
    flowmbd.NumericalError
        The belt could not be mounted.

    Example
    -------
    >>> sim = flowmbd.belt.Simulation({"model": "flowing"})
    >>> sim.run_to(0.5, observer=lambda s: print(s.t, s.pulley_speeds), every=100)
    >>> sim.report()["balances"]["torque_residual_rel"]
    """

    def __init__(self, config: Optional[Mapping[str, Any]] = None) -> None:
        self._sim = _native.BeltSimulation(config_json(config))

    model = Native("The model kind.")
    step_size = Native("The step [s].")
    t = Native("Time [s].")
    q = Native("Coordinates (numpy copy; names in ``coordinate_names``).")
    v = Native("Velocities (numpy copy).")
    coordinate_names = Native("The name of every coordinate.")
    pulley_speeds = Native(
        "Pulley speeds in the belt's travel sense [rad/s], in the layout's order (numpy)."
    )
    belt_speed = Native("Belt speed along its path [m/s].")
    arm_angle = Native("Tensioner arm angle [rad] (``None`` without a tensioner).")

    def state(self) -> tuple:
        """The state ``(t, q, v)`` (copies), to restart from with ``set_state``."""
        return (self._sim.t, self._sim.q, self._sim.v)

    def set_state(self, t: float, q: Any, v: Any) -> None:
        """Restart from the state ``(t, q, v)`` (same model and step)."""
        import numpy as np

        self._sim.set_state(
            _args.number("t", t),
            np.ascontiguousarray(q, dtype=float),
            np.ascontiguousarray(v, dtype=float),
        )


    def set_signal(self, pulley: int, signal: Mapping[str, Any]) -> None:
        """Replace the signal of ``pulley`` (index in the layout) from now on: a driver's speed
        [rad/s] or an accessory's load torque [N m], as a signal dict of a layout (e.g.
        ``{"kind": "constant", "value": 10.0}`` or ``{"kind": "schedule", "knots": [[0.5, 0],
        [0.6, 10]]}``); an idler becomes a loaded pulley."""
        if not isinstance(signal, Mapping):
            raise ValueError(f"signal: expected a dict, got {type(signal).__name__}")
        self._sim.set_signal(_args.count("pulley", pulley), config_json(signal))

    def report(self) -> Result:
        """The report of the current state: ``pulleys`` (speed, arcs, slip velocities, hub
        load, torque, power, torque residual), ``spans`` (force [N]), ``balances`` (torque
        and power residuals)."""
        return from_json(self._sim.report())


def wave(
    config: Optional[Mapping[str, Any]] = None,
    speed: Optional[float] = None,
    t_end: Optional[float] = None,
    series: bool = False,
) -> Result:
    """The rotating vs non-rotating belt of Ribaric §6.2, Fig. 6-3 (``flowmbd-belt wave``): the
    flowing-material belt drive of Table 6-1 with its upper span deflected by a bump and let
    go, once at rest and once running at ``wave.belt_speed``. The running span vibrates lower,
    by the travelling string's ``1 − v²/c²`` (Wickert and Mote), and its deflection drifts with
    the belt.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-belt wave --print-config`` (``drive``,
        ``flowing``, ``wave``, ``vtk_frames``, ``vtk_scale``).
    speed : belt speed of the running case [m/s] (replaces ``config["wave"]["belt_speed"]``;
        the CLI's ``--speed``).
    t_end : simulated time [s] (replaces ``config["wave"]["t_end"]``; the CLI's ``--t-end``).
    series : also return ``"wave"``: the columns of the CLI's ``wave.csv`` as numpy arrays
        (``t_s`` [s], ``midspan_rest_m``, ``midspan_running_m`` [m]: mid-span deflection,
        ``centroid_rest_m``, ``centroid_running_m`` [m]: centroid of the span deflection along
        the span).

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``wave_speed`` [m/s], ``rest`` and ``running`` (each
        ``belt_speed`` [m/s], ``frequency_hz`` [Hz], ``centroid_speed`` [m/s]),
        ``frequency_ratio``, ``frequency_ratio_string``, ``wall_time_s`` [s] and ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        A run failed.
    """
    text, data = _native.wave(
        config_json(config),
        _args.optional_number("speed", speed),
        _args.optional_number("t_end", t_end),
    )
    return with_series(text, data, series)


def demo(
    config: Optional[Mapping[str, Any]] = None,
    t_end: Optional[float] = None,
    series: bool = False,
) -> Result:
    """The rigid slider-crank demonstration (``flowmbd-belt demo``): the crank driven at
    constant speed, integrated by the shared generalized-α stepper with its joints as index-3
    constraints, and the slider position compared with the closed-form kinematics
    ``x = a cos θ + sqrt(b² − a² sin² θ)``.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-belt demo --print-config`` (``crank_length``,
        ``rod_length`` [m], ``masses`` [kg] (crank, rod, slider), ``omega`` [rad/s],
        ``theta0`` [rad], ``t_end`` [s], ``step`` [s], ``rho_inf``).
    t_end : simulated time [s] (replaces ``config["t_end"]``; the CLI's ``--t-end``).
    series : also return ``"history"``: the columns of the CLI's ``history.csv`` as numpy
        arrays (``t_s`` [s], ``theta_rad`` [rad], ``slider_x_m`` and ``closed_form_x_m`` [m]).

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``max_slider_error_m`` [m], ``steps``,
        ``newton_iterations``, ``wall_time_s`` [s] and ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        The integration failed.
    """
    text, data = _native.demo(config_json(config), _args.optional_number("t_end", t_end))
    return with_series(text, data, series)
