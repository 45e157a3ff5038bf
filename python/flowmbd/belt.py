"""Belt drives: the speed-loss study of Ribaric §6.4–6.5 (``flowmbd-belt speed-loss``)."""

from __future__ import annotations

from typing import Any, Mapping, Optional, Sequence

from . import _native
from ._results import config_json, from_json


def speed_loss(
    omega: Optional[float] = 62.8,
    torques: Optional[Sequence[float]] = (0.0, 10.0),
    model: Optional[str] = "flowing",
    config: Optional[Mapping[str, Any]] = None,
) -> dict:
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
        The content of the CLI's ``summary.json`` (``omega_driver``, ``model``, ``points``
        (list of ``{"torque", "delta_omega"}``), ``analytical`` (array), ``cases``,
        ``modal_coordinates``, ``wall_time_s``).

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
            None if omega is None else float(omega),
            None if torques is None else [float(t) for t in torques],
            model,
        )
    )
