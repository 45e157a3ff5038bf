"""Summaries as Python objects: the content of a study's ``summary.json``, with every list of
numbers turned into a numpy array (lists of objects stay lists of dicts)."""

from __future__ import annotations

import json
from typing import Any, Mapping, Optional

import numpy as np


def _is_number(x: Any) -> bool:
    return (isinstance(x, (int, float)) and not isinstance(x, bool)) or x is None


#: Keys of small geometric vectors (a force or a position with 2 or 3 components): they stay
#: plain lists, so that a summary's per-point objects compare with ``==`` like the CLI's JSON.
VECTOR_KEYS = frozenset({"force", "hub_load", "position", "center"})


def to_result(value: Any) -> Any:
    """Convert decoded JSON: numeric lists (``null`` = NaN) become float arrays, nested
    numeric lists become 2-D arrays, geometric vectors under :data:`VECTOR_KEYS` stay lists,
    everything else is kept."""
    if isinstance(value, dict):
        return {
            k: v if k in VECTOR_KEYS and isinstance(v, list) and len(v) <= 3 else to_result(v)
            for k, v in value.items()
        }
    if isinstance(value, list):
        if value and all(_is_number(x) for x in value):
            return np.array([np.nan if x is None else x for x in value], dtype=float)
        if value and all(
            isinstance(r, list) and r and all(_is_number(x) for x in r) for r in value
        ) and len({len(r) for r in value}) == 1:
            return np.array(
                [[np.nan if x is None else x for x in r] for r in value], dtype=float
            )
        return [to_result(v) for v in value]
    return value


def from_json(text: str) -> dict:
    """A summary returned by the native module."""
    return to_result(json.loads(text))


def config_json(config: Optional[Mapping[str, Any]]) -> Optional[str]:
    """The configuration dict (TOML keys) as JSON text for the native module."""
    if config is None:
        return None
    if not isinstance(config, Mapping):
        raise ValueError(f"config: expected a dict with the TOML keys, got {type(config).__name__}")

    def plain(v: Any, depth: int = 0) -> Any:
        if depth > 64:
            raise ValueError("nested more than 64 levels deep")
        if isinstance(v, np.ndarray):
            return v.tolist()
        if isinstance(v, np.generic):
            return v.item()
        if isinstance(v, Mapping):
            return {str(k): plain(x, depth + 1) for k, x in v.items()}
        if isinstance(v, (list, tuple)):
            return [plain(x, depth + 1) for x in v]
        return v

    try:
        return json.dumps(plain(config), allow_nan=True)
    except (TypeError, ValueError, OverflowError, RecursionError) as e:
        # a value JSON cannot hold, a circular or absurdly deep dict (issue 35)
        raise ValueError(f"config: cannot be read as a configuration: {type(e).__name__}: {e}") from e
