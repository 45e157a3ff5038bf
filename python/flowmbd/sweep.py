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


def _row(params: dict, result: Any, error: Optional[str]) -> dict:
    row = dict(params)
    if isinstance(result, Mapping):
        for k, v in result.items():
            if _scalar(v) and k not in row:
                row[k] = v.item() if isinstance(v, (np.ndarray, np.generic)) else v
    elif _scalar(result) and result is not None:
        row["result"] = result
    row["error"] = error
    return row


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

    A point whose ``fn`` raises is recorded with its error (not retried: the models are
    deterministic). A point whose worker dies is rescheduled on another worker by the Dask
    scheduler (up to ``distributed.scheduler.allowed-failures`` times, then recorded as
    ``KilledWorker``).

    Returns
    -------
    pandas.DataFrame
        One row per point in grid order: the parameters, the scalar results and ``error``
        (``None``, or ``"Type: message"`` of a failed point, e.g. ``"ValueError: omegas[0]:
        must be finite and > 0 [rad/s]"`` or a ``KilledWorker`` after repeated worker deaths).
    """
    import pandas as pd

    pts = points(grid)
    rows: List[Optional[dict]] = [None] * len(pts)
    bar = _bar(len(pts), progress)
    try:
        if client is False:
            for i, p in enumerate(pts):
                status, value = _run_point(fn, p)
                rows[i] = _row(p, value if status == "ok" else None,
                               None if status == "ok" else value)
                if bar is not None:
                    bar.update(1)
        else:
            _distributed(fn, pts, client, rows, bar)
    finally:
        if bar is not None:
            bar.close()
    return pd.DataFrame(rows)


def _distributed(fn, pts, client, rows, bar):
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
            rows[i] = _row(pts[i], value if status == "ok" else None,
                           None if status == "ok" else value)
            fut.release()
            if bar is not None:
                bar.update(1)
    finally:
        if own is not None:
            own[1].close()
            own[0].close()
