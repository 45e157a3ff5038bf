"""Design sweeps on Dask distributed: ``flowmbd.sweep(fn, grid, client=None)``."""

from __future__ import annotations

import itertools
import numbers
from typing import Any, Callable, Iterable, List, Mapping, Optional, Sequence, Union

import numpy as np

Grid = Union[Mapping[str, Sequence[Any]], Iterable[Mapping[str, Any]]]


def points(grid: Grid) -> List[dict]:
    """The points of ``grid``: a dict of lists is expanded to its Cartesian product (keys in
    the given order, the last key varying fastest); a list of dicts is taken as it is."""
    if isinstance(grid, Mapping):
        keys = list(grid)
        values = []
        for k in keys:
            v = grid[k]
            if isinstance(v, (str, bytes)) or not isinstance(v, Iterable):
                raise ValueError(f"grid[{k!r}]: expected a list of values, got {v!r}")
            values.append(list(v))
        return [dict(zip(keys, combo)) for combo in itertools.product(*values)]
    out = []
    for i, p in enumerate(grid):
        if not isinstance(p, Mapping):
            raise ValueError(f"grid[{i}]: expected a dict of parameters, got {p!r}")
        out.append(dict(p))
    return out


def _scalar(v: Any) -> bool:
    if isinstance(v, np.ndarray):
        return v.ndim == 0
    return v is None or isinstance(v, (numbers.Number, str, bool, np.generic))


#: Result keys left out of the rows unless selected: prose, not data.
_PROSE_KEYS = ("meaning",)


def _path(result: Any, path: str) -> Any:
    """The value at the dotted ``path`` of a nested result (``"points.1.delta_omega"``: keys of
    dicts, indices of lists and arrays)."""
    v = result
    for step in path.split("."):
        if isinstance(v, Mapping):
            if step not in v:
                raise KeyError(f"select {path!r}: no key {step!r} (keys: {', '.join(map(str, v))})")
            v = v[step]
        elif isinstance(v, (list, tuple, np.ndarray)):
            try:
                v = v[int(step)]
            except (ValueError, IndexError):
                raise KeyError(f"select {path!r}: {step!r} is not an index of a list of {len(v)}")
        else:
            raise KeyError(f"select {path!r}: {step!r} reaches into a {type(v).__name__}")
    return v


def _plain(v: Any) -> Any:
    return v.item() if isinstance(v, (np.ndarray, np.generic)) and np.ndim(v) == 0 else v


def _rows(params: dict, result: Any, error: Optional[str], select, explode) -> List[dict]:
    """The rows of one point: one, or one per element of ``result[explode]``."""
    row = dict(params)
    if error is None and isinstance(result, Mapping):
        for k, v in result.items():
            if _scalar(v) and k not in row and k not in _PROSE_KEYS:
                row[k] = _plain(v)
        for name, how in (select or {}).items():
            try:
                row[name] = _plain(how(result) if callable(how) else _path(result, how))
            except (KeyboardInterrupt, SystemExit):
                raise
            except Exception as e:  # a selection that does not fit this result
                error = f"{type(e).__name__}: {e}"
                break
    elif error is None and _scalar(result) and result is not None:
        row["result"] = result
    if explode is None or error is not None:
        row["error"] = error
        return [row]
    try:
        items = _path(result, explode)
    except KeyError as e:
        row["error"] = f"KeyError: {e}"
        return [row]
    out = []
    for i, item in enumerate(items):
        r = dict(row)
        r[f"{explode}_index"] = i
        if isinstance(item, Mapping):
            for k, v in item.items():
                if _scalar(v) and k not in params:
                    r[k] = _plain(v)
        elif _scalar(item):
            r[explode] = _plain(item)
        r["error"] = None
        out.append(r)
    return out


def _run_point(fn: Callable[..., Any], params: dict):
    """One point on a worker: ``("ok", result)`` or ``("error", "Type: message")`` (so that a
    failing point is recorded instead of aborting the sweep)."""
    try:
        return "ok", fn(**params)
    except (KeyboardInterrupt, SystemExit, GeneratorExit):
        raise
    except BaseException as e:  # recorded per point, by design
        # BaseException: a Rust panic reaches Python as pyo3's PanicException, which is not
        # an Exception; it is recorded like any failure (issue 35), never left hanging
        return "error", f"{type(e).__name__}: {e}"


def _bar(total: int, show: bool):
    try:
        from tqdm.auto import tqdm
    except ImportError:  # progress bar is optional
        return None
    return tqdm(total=total, desc="flowmbd sweep", unit="point", disable=not show)


def sweep(
    fn: Callable[..., Any],
    grid: Grid,
    client: Any = None,
    *,
    progress: bool = True,
    select: Optional[Mapping[str, Union[str, Callable[[Any], Any]]]] = None,
    explode: Optional[str] = None,
):
    """Run ``fn(**params)`` for every point of ``grid`` and collect one row per point.

    Parameters
    ----------
    fn : a picklable function of the parameters; it returns a dict (its scalar values become
        columns; arrays and lists are left out) or a scalar (column ``result``).
    grid : a dict of lists (Cartesian product) or a list of dicts.
    client : a ``dask.distributed.Client`` (a cluster through a scheduler address or
        dask-jobqueue); ``None`` starts a ``LocalCluster`` with one single-threaded worker
        process per core for this sweep; ``False`` runs the points one after the other in
        this process (no Dask).
    progress : show a progress bar (tqdm) while results stream back.
    select : extra columns taken from inside each result: ``{"column": "dotted.path"}`` (keys
        of dicts, indices of lists: ``"points.1.delta_omega"``, ``"cases.0.capacity"``) or
        ``{"column": callable}`` (called with the result). A path that does not fit a result
        records the point's ``error``.
    explode : a dotted path to a list in each result (``"points"``): one row per element,
        with the element's scalar values as columns and ``<explode>_index``; a point that
        failed keeps one row with its ``error``.

    The ``meaning`` paragraph of a study's summary is not a column (select it to have it).

    A point whose ``fn`` raises is recorded with its error (not retried: the models are
    deterministic). A point whose worker dies is rescheduled on another worker by the Dask
    scheduler (up to ``distributed.scheduler.allowed-failures`` times, then recorded as
    ``KilledWorker``).

    Returns
    -------
    pandas.DataFrame
        One row per point (or per element of ``explode``) in grid order: the parameters, the
        scalar results, the selected columns and ``error``
        (``None``, or ``"Type: message"`` of a failed point, e.g. ``"ValueError: omegas[0]:
        must be finite and > 0 [rad/s]"`` or a ``KilledWorker`` after repeated worker deaths).
    """
    import pandas as pd

    pts = points(grid)
    if select is not None:
        if not isinstance(select, Mapping):
            raise ValueError(f"select: expected a dict of column: path or callable, got {type(select).__name__}")
        for name, how in select.items():
            if not (callable(how) or isinstance(how, str)):
                raise ValueError(f"select[{name!r}]: expected a dotted path or a callable, got {how!r}")
    if explode is not None and not isinstance(explode, str):
        raise ValueError(f"explode: expected a dotted path, got {explode!r}")
    rows: List[Optional[List[dict]]] = [None] * len(pts)
    bar = _bar(len(pts), progress)
    try:
        if client is False:
            for i, p in enumerate(pts):
                status, value = _run_point(fn, p)
                rows[i] = _rows(p, value if status == "ok" else None,
                                None if status == "ok" else value, select, explode)
                if bar is not None:
                    bar.update(1)
        else:
            _distributed(fn, pts, client, rows, bar, select, explode)
    finally:
        if bar is not None:
            bar.close()
    return pd.DataFrame([r for point in rows for r in point])


def _distributed(fn, pts, client, rows, bar, select, explode):
    from dask.distributed import Client, LocalCluster, as_completed

    own = None
    if client is None:
        import os

        cluster = LocalCluster(
            n_workers=max(1, min(len(pts), os.cpu_count() or 1)),
            threads_per_worker=1,
            processes=True,
            dashboard_address=":0",
        )
        own = (cluster, Client(cluster))
        client = own[1]
    try:
        futures = [
            client.submit(_run_point, fn, p, pure=False) for p in pts
        ]
        index = {f.key: i for i, f in enumerate(futures)}
        for fut in as_completed(futures):
            i = index[fut.key]
            try:
                status, value = fut.result()
            except (KeyboardInterrupt, SystemExit, GeneratorExit):
                raise
            except BaseException as e:  # the task itself failed (e.g. KilledWorker)
                status, value = "error", f"{type(e).__name__}: {e}"
            rows[i] = _rows(pts[i], value if status == "ok" else None,
                            None if status == "ok" else value, select, explode)
            fut.release()
            if bar is not None:
                bar.update(1)
    finally:
        if own is not None:
            own[1].close()
            own[0].close()
