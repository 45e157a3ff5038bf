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


class Result(dict):
    """A study's summary: the ``summary.json`` content as a dict (:func:`to_result`), with
    :meth:`to_dataframe` for its per-point records."""

    def records(self) -> str:
        """The default record list of :meth:`to_dataframe`: ``"points"``, else ``"cases"``,
        else the first key holding a list of dicts."""
        for key in ("points", "cases"):
            if isinstance(self.get(key), list):
                return key
        for key, v in self.items():
            if isinstance(v, list) and v and all(isinstance(x, Mapping) for x in v):
                return key
        raise KeyError(f"no list of records in this result (keys: {', '.join(self)})")

    def to_dataframe(self, records: Optional[str] = None, explode: Optional[str] = None):
        """A pandas DataFrame of the records at the dotted path ``records`` (default
        :meth:`records`, e.g. ``"points"``): one row per record with its scalar fields (numbers,
        strings, flags; nested lists and dicts are left out), or with ``explode`` (a key of each
        record holding a list, e.g. ``"pulleys"``) one row per element of that list, with the
        record's scalar fields, ``<records>_index``, ``<explode>_index`` and the element's
        scalar fields (units as in the field names and the study's docstring).

        Needs pandas (``pip install "./python[sweep]"``)."""
        try:
            import pandas as pd
        except ImportError as e:
            raise ImportError(
                'to_dataframe needs pandas: pip install pandas (or the "sweep" extra)'
            ) from e
        from .sweep import _path, _rows

        path = self.records() if records is None else records
        items = _path(self, path)
        if not isinstance(items, list):
            raise KeyError(f"records {path!r}: a {type(items).__name__}, not a list of records")
        index = f"{path.rsplit('.', 1)[-1]}_index"
        rows = []
        for i, item in enumerate(items):
            if not isinstance(item, Mapping):
                raise KeyError(f"records {path!r}: element {i} is a {type(item).__name__}")
            for r in _rows({index: i}, item, None, None, explode):
                if r.get("error") is not None:
                    raise KeyError(f"records {path!r}, element {i}: {r['error']}")
                r.pop("error", None)
                rows.append(r)
        return pd.DataFrame(rows)


def from_json(text: str) -> Result:
    """A summary returned by the native module."""
    return Result(to_result(json.loads(text)))


def with_series(text: str, series_data: Mapping[str, Any], series: bool) -> Result:
    """The summary JSON ``text`` as a :class:`Result`, with the CSV series
    (``{file stem: {column: array}}``) added when ``series``."""
    out = from_json(text)
    if series:
        out.update(series_data)
    return out


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
