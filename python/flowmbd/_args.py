"""Checks of the arguments of the public functions: a bad argument raises ``ValueError``
naming it, never ``TypeError``, ``OverflowError`` or ``RecursionError`` from somewhere inside
(issue 35)."""

from __future__ import annotations

import math
import numbers
from typing import Any, List, Optional

#: Largest count accepted from Python (the native module's ``usize``; the libraries bound the
#: counts they allocate from much lower, with messages naming the field).
MAX_COUNT = 2**63 - 1


def number(name: str, value: Any) -> float:
    """``value`` as a float (NaN and infinities pass through: the library's checks name them)."""
    if isinstance(value, bool) or not isinstance(value, (numbers.Real, str)) and not hasattr(
        value, "__float__"
    ):
        raise ValueError(f"{name}: expected a number, got {type(value).__name__}")
    try:
        return float(value)
    except (TypeError, ValueError, OverflowError) as e:
        raise ValueError(f"{name}: expected a number, got {value!r:.60}") from e


def optional_number(name: str, value: Any) -> Optional[float]:
    """:func:`number`, or ``None``."""
    return None if value is None else number(name, value)


def numbers_list(name: str, values: Any) -> List[float]:
    """A sequence of numbers as floats (a string or a scalar is refused)."""
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise ValueError(f"{name}: expected a list of numbers, got {type(values).__name__}")
    try:
        items = list(values)
    except (TypeError, ValueError, OverflowError, RecursionError) as e:
        raise ValueError(f"{name}: expected a list of numbers ({e})") from e
    return [number(f"{name}[{i}]", v) for i, v in enumerate(items)]


def optional_numbers(name: str, values: Any) -> Optional[List[float]]:
    """:func:`numbers_list`, or ``None``."""
    return None if values is None else numbers_list(name, values)


def count(name: str, value: Any) -> int:
    """A non-negative integer (``True``, 2.5, ``"3"``, NaN, infinities and values past the
    native ``usize`` are refused)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"{name}: must be a non-negative integer, got {value!r:.60}")
    if isinstance(value, numbers.Integral):
        n = int(value)
    else:
        v = float(value)
        if not math.isfinite(v) or v != math.floor(v):
            raise ValueError(f"{name}: must be a non-negative integer, got {value!r:.60}")
        n = int(v)
    if n < 0 or n > MAX_COUNT:
        raise ValueError(f"{name}: must be a non-negative integer below 2**63, got {n}")
    return n


def optional_count(name: str, value: Any) -> Optional[int]:
    """:func:`count`, or ``None``."""
    return None if value is None else count(name, value)
