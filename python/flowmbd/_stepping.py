"""What the Python ``Simulation`` classes (:class:`flowmbd.belt.Simulation`,
:class:`flowmbd.tire.Simulation`) share: read-only attributes of their native simulation and the
observed time loop (:class:`Stepping`)."""

from __future__ import annotations

from typing import Any, Optional

from . import _args


class Native:
    """A read-only attribute of a ``Simulation``: its native simulation's attribute of the same
    name."""

    def __init__(self, doc: str) -> None:
        self.__doc__ = doc

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    def __get__(self, obj: Any, owner: Optional[type] = None) -> Any:
        return self if obj is None else getattr(obj._sim, self.name)

    def __set__(self, obj: Any, value: Any) -> None:
        raise AttributeError(f"{self.name}: read-only")


class Stepping:
    """The time loop of a ``Simulation``: its native simulation ``_sim`` stepped ``n`` steps or
    to a time, with an optional observer."""

    _sim: Any

    def step(self, n: int = 1) -> None:
        """Take ``n`` steps of the simulation's step (a belt drive's failed step is subdivided
        first); a step that fails raises ``flowmbd.NumericalError`` and keeps the state
        reached."""
        self._sim.step(_args.count("n", n))

    def run_to(self, t_end: float, observer: Optional[Any] = None, every: int = 1) -> None:
        """Step until ``t_end`` [s]; ``observer(sim)`` is called after every ``every``-th step
        (and at the end). An exception in the observer stops the run and propagates."""
        t_end = _args.number("t_end", t_end)
        sim = self._sim
        if observer is None:
            sim.run_to(t_end)
            return
        every = _args.count("every", every)
        if every < 1:
            raise ValueError("every: must be at least 1")
        if not callable(observer):
            raise ValueError(f"observer: expected a callable, got {type(observer).__name__}")
        h = sim.step_size
        while sim.t < t_end - 0.5 * h:
            left = int(round((t_end - sim.t) / h))
            sim.step(max(1, min(every, left)))
            observer(self)
