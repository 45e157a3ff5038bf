"""Point functions for the sweep tests (pickled by value to the workers)."""

import os
import pathlib

import flowmbd


def string_point(speed, nodes=30):
    """Lowest flowing-model frequency of the travelling string at `speed`."""
    r = flowmbd.string.modes(speed=speed, nodes=nodes, modes=10)
    return {"f1_hz": r["flowing_hz"][0], "f1_galerkin_hz": r["analytical_hz"][0],
            "critical_speed": r["critical_speed"]}


def dying_point(speed, marker_dir):
    """Like string_point, but the worker process dies (os._exit, no clean-up) the first time
    it runs speed == 10: a crash in the middle of the sweep."""
    marker = pathlib.Path(marker_dir) / f"died-{speed}"
    if speed == 10.0 and not marker.exists():
        marker.write_text(str(os.getpid()))
        os._exit(1)
    return string_point(speed)


def cleat_point(speed_kmh, tire):
    """Cleat summary scalars of a short run with a reduced tire (shipped by Dask)."""
    r = flowmbd.tire.cleat(speed_kmh=speed_kmh, config={"rig": {"settle_time": 0.05,
                                                              "record_time": 0.05}}, tire=tire)
    return {k: v for k, v in r.items() if k in ("fy_rms", "fx_rms", "fy_peak_hz", "steps")}
