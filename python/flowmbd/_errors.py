"""Errors raised by flowmbd."""

from __future__ import annotations

import json
from typing import Any, Optional


class NumericalError(RuntimeError):
    """A computation failed (the CLI's exit code 1).

    ``partial`` holds the results computed before the failure (the ``partial`` object of the
    CLI's ``summary.json``) as a :class:`flowmbd.Result` (a dict) or, for a sweep, the list of
    the runs done, or ``None`` when nothing was computed.
    """

    def __init__(self, message: str, partial: Optional[Any] = None) -> None:
        super().__init__(message)
        if isinstance(partial, str):
            from ._results import Result, to_result

            # a summary (dict) becomes a Result; a list (the runs of a sweep) stays a list
            value = to_result(json.loads(partial))
            partial = Result(value) if isinstance(value, dict) else value
        self.partial = partial

    def __reduce__(self):  # picklable, so that Dask can send it back from a worker
        return (type(self), (str(self), self.partial))
