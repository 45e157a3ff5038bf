"""ANCF beams of Kerkkänen (2006) §2.4: the five studies of ``flowmbd-beam``
(``simply-supported``, ``cantilever``, ``pendulum``, ``spinning``, ``ground-contact``), through
the same library functions as the CLI. Series that the CLI writes as CSV files come back with
``series=True``: under the CSV file's name without ``.csv``, a dict of its columns as numpy
arrays. ``element`` is ``"proposed"`` (Kerkkänen's 8-DOF shear-deformable element) or
``"omar-shabana"`` (the 12-DOF Omar–Shabana element)."""

from __future__ import annotations

from typing import Any, Mapping, Optional

from . import _args, _native
from ._results import Result, config_json, from_json, with_series


def _element(element: Any) -> Optional[str]:
    if element is None or isinstance(element, str):
        return element
    raise ValueError(
        f'element: expected "proposed" or "omar-shabana", got {type(element).__name__}'
    )


def _dynamic(native: Any, config: Any, elements: Any, series: bool) -> Result:
    """A dynamic study (``native``: the pendulum's or the spinning beam's) with its history."""
    text, data = native(config_json(config), _args.optional_count("elements", elements))
    return with_series(text, data, series)


def simply_supported(
    config: Optional[Mapping[str, Any]] = None,
    element: Optional[str] = None,
    nu: Optional[float] = None,
    elements: Optional[int] = None,
) -> Result:
    """The simply supported beam under a 1000 N mid-point load (``flowmbd-beam
    simply-supported``; Kerkkänen Tables 2.1 (ν = 0) and 2.2 (ν = 0.3)): L = 2 m, width 0.1 m,
    E = 2.07·10¹¹ Pa, first node pinned, last on a roller.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-beam simply-supported --print-config``
        (``element``, ``elements``, ``nu``, ``height`` [m], ``width`` [m], ``length`` [m],
        ``young`` [Pa], ``density`` [kg/m³], ``increments``); default Table 2.1's 8 proposed
        elements, h = 0.1 m, ν = 0.
    element, nu, elements : replace ``config["element"]``, ``config["nu"]`` (Poisson's ratio
        [-]) and ``config["elements"]`` (even) (the CLI's ``--element``, ``--nu``,
        ``--elements``; ``None`` keeps them).

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``midpoint_deflection_mm`` (vertical position of the
        mid-point [mm], Kerkkänen Tables 2.1/2.2) and ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message, e.g. an odd ``elements``).
    flowmbd.NumericalError
        The Newton solve failed, or the deflection exceeds half the beam's length.
    """
    return from_json(
        _native.beam_simply_supported(
            config_json(config),
            _element(element),
            _args.optional_number("nu", nu),
            _args.optional_count("elements", elements),
        )
    )


def cantilever(
    config: Optional[Mapping[str, Any]] = None,
    element: Optional[str] = None,
    h: Optional[float] = None,
    nu: Optional[float] = None,
    elements: Optional[int] = None,
    series: bool = False,
) -> Result:
    """The large-deflection cantilever under the tip force −5·10⁸ h³ N (``flowmbd-beam
    cantilever``; Kerkkänen Tables 2.3/2.4, Fig. 2.4).

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-beam cantilever --print-config``: ``beam`` (the
        keys of :func:`simply_supported`'s config) and ``shape_segments`` (segments per element
        of the deformed shape); default Table 2.3's Model 1 (8 proposed elements, h = 0.1 m,
        ν = 0.3, 10 load increments).
    element, h, nu, elements : replace ``config["beam"]``'s ``element``, ``height`` [m],
        ``nu`` [-] and ``elements`` (the CLI's ``--element``, ``--h``, ``--nu``,
        ``--elements``; ``None`` keeps them).
    series : also return ``"shape"``: the columns of ``shape.csv`` (``x_m``, ``y_m``, the
        deformed centreline [m], root first).

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``tip`` (deformed tip position (x, y) [m], Kerkkänen
        Tables 2.3/2.4) and ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message, e.g. ``beam.nu: …``).
    flowmbd.NumericalError
        The Newton solve failed, or the tip lies further than twice the length from the clamp.
    """
    text, data = _native.beam_cantilever(
        config_json(config),
        _element(element),
        _args.optional_number("h", h),
        _args.optional_number("nu", nu),
        _args.optional_count("elements", elements),
    )
    return with_series(text, data, series)


def pendulum(
    config: Optional[Mapping[str, Any]] = None,
    elements: Optional[int] = None,
    series: bool = False,
) -> Result:
    """The falling flexible pendulum (``flowmbd-beam pendulum``; Kerkkänen Figs 2.6/2.7):
    L = 2 m, 0.1 m square section, E = 2.07·10⁷ Pa, pinned at one end and released horizontally
    under gravity, integrated by the generalized-α method.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-beam pendulum --print-config`` (``element``,
        ``elements``, ``length`` [m], ``side`` [m], ``young`` [Pa], ``nu`` [-], ``density``
        [kg/m³], ``gravity`` [m/s²], ``t_end`` [s], ``h`` (step) [s], ``rho_inf`` [-]);
        default 4 proposed elements, 1 s with 50 µs steps.
    elements : replaces ``config["elements"]`` (the CLI's ``--elements``).
    series : also return ``"history"``: the columns of ``history.csv`` (``t_s`` [s],
        ``tip_x_m``, ``tip_y_m`` [m], ``kinetic_J``, ``strain_J``, ``potential_J``,
        ``total_J`` [J]; about 2000 samples).

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``elements``, ``max_energy_deviation_j`` (largest
        deviation of T + U + V from its initial value [J]; the thesis reports 0.62·10⁻⁴ J),
        ``min_tip_y_m`` [m], ``final_tip`` [m], ``max_kinetic_j`` [J] and ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        The time integration failed, or the result is implausible.
    """
    return _dynamic(_native.beam_pendulum, config, elements, series)


def spinning(
    config: Optional[Mapping[str, Any]] = None,
    elements: Optional[int] = None,
    series: bool = False,
) -> Result:
    """The spinning beam (``flowmbd-beam spinning``; Kerkkänen Figs 2.10/2.11, Wu & Haug): the
    hub spins up to ω along (2.35) and the beam stretches under the centrifugal load; the
    steady extension is compared with the closed form (2.37) and the value printed in the
    thesis.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-beam spinning --print-config`` (``elements``,
        ``length`` [m], ``width``, ``height`` [m], ``young`` [Pa], ``nu`` [-], ``density``
        [kg/m³], ``omega`` [rad/s], ``spin_up`` [s], ``t_end`` [s], ``h`` [s], ``rho_inf``).
    elements : replaces ``config["elements"]`` (the CLI's ``--elements``).
    series : also return ``"history"``: the columns of ``history.csv`` (``t_s`` [s],
        ``tip_x_m``, ``tip_y_m`` [m], ``axial_extension_m`` [m], ``tip_offset_m`` [m, from the
        rigid shadow beam], ``kinetic_J``, ``strain_J`` [J]; about 4000 samples).

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``steady_extension_m`` (mean axial extension over the last
        10 % of the run [m]), ``analytical_extension_m`` ((2.37) with the configuration's data
        [m]), ``printed_extension_m`` [m], ``relative_error`` [-], ``max_tip_offset_m`` [m] and
        ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        The time integration failed, or the result is implausible.
    """
    return _dynamic(_native.beam_spinning, config, elements, series)


def ground_contact(
    config: Optional[Mapping[str, Any]] = None,
    element: Optional[str] = None,
    elements: Optional[int] = None,
    load_factor: Optional[float] = None,
    series: bool = False,
) -> Result:
    """A cantilever pressed onto rigid ground by the line load q = f·q* (``flowmbd-beam
    ground-contact``), with frictionless unilateral Lagrange contact at the nodes, against the
    Euler–Bernoulli closed forms: critical load q* = 72 EI g₀/L⁴; for q > q* the beam lies flat
    from a = (72 EI g₀/q)^(1/4) to the tip with total contact force qL − 2qa/3.

    Parameters
    ----------
    config : dict with the keys of ``flowmbd-beam ground-contact --print-config``
        (``element``, ``elements``, ``length``, ``height``, ``width`` [m], ``young`` [Pa],
        ``nu`` [-], ``gap`` (initial gap g₀) [m], ``load_factor`` [-], ``increments``);
        default 64 proposed elements, L = 1 m, h = 0.01 m, f = 4.
    element, elements, load_factor : replace the configuration's (the CLI's ``--element``,
        ``--elements``, ``--load-factor``).
    series : also return ``"contact"``: the columns of ``contact.csv`` (``x_m``, ``y_m``,
        deformed node position [m]; ``contact_force_N`` [N]).

    Returns
    -------
    Result
        The CLI's ``summary.json``: ``line_load`` and ``critical_load`` [N/m],
        ``total_force`` and ``euler_bernoulli_total_force`` [N], ``first_contact_x`` [m]
        (``None`` without contact) and ``euler_bernoulli_contact_start`` [m], ``meaning``.

    Raises
    ------
    ValueError
        Bad input (the CLI's ``field: reason`` message).
    flowmbd.NumericalError
        The contact solve failed, or a contact force is tensile.
    """
    text, data = _native.beam_ground_contact(
        config_json(config),
        _element(element),
        _args.optional_count("elements", elements),
        _args.optional_number("load_factor", load_factor),
    )
    return with_series(text, data, series)
