"""Travelling string: the modes study of Ribaric §4.2.3 (``flowmbd-string modes``)."""

from __future__ import annotations

from typing import Any, Mapping, Optional

from . import _args, _native
from ._results import Result, config_json, from_json


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
            None if nodes is None else _args.count("nodes", nodes),
            None if modes is None else _args.count("modes", modes),
        )
    )

