"""flowmbd.sweep on a 2-worker Dask LocalCluster against the serial loop (reference: the
same function called point by point in this process)."""

import sys

import cloudpickle
import numpy as np
import pandas as pd
import pytest
from dask.distributed import Client, LocalCluster

import flowmbd
import sweep_points

# the workers cannot import the test folder: ship the point functions by value
cloudpickle.register_pickle_by_value(sweep_points)

SPEEDS = [0.0, 5.0, 10.0, 15.0, 20.0, 25.0]


@pytest.fixture(scope="module")
def client():
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                           dashboard_address=":0")
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()


def serial():
    return pd.DataFrame(
        [{"speed": s, **sweep_points.string_point(s), "error": None} for s in SPEEDS]
    )


def test_points_of_a_grid():
    assert flowmbd.points({"a": [1, 2], "b": ["x", "y", "z"]})[1] == {"a": 1, "b": "y"}
    assert len(flowmbd.points({"a": [1, 2], "b": ["x", "y", "z"]})) == 6
    assert flowmbd.points([{"a": 1}, {"a": 5}]) == [{"a": 1}, {"a": 5}]
    with pytest.raises(ValueError):
        flowmbd.points({"a": 3})


def test_local_cluster_equals_serial(client):
    df = flowmbd.sweep(sweep_points.string_point, {"speed": SPEEDS}, client=client,
                       progress=False)
    ref = serial()
    assert list(df.columns) == list(ref.columns)
    assert len(df) == len(SPEEDS)
    pd.testing.assert_frame_equal(df, ref, check_exact=True)
    # and the in-process mode of sweep itself
    pd.testing.assert_frame_equal(
        flowmbd.sweep(sweep_points.string_point, [{"speed": s} for s in SPEEDS], client=False,
                      progress=False),
        ref, check_exact=True)


def test_failed_point_is_recorded(client):
    df = flowmbd.sweep(sweep_points.string_point, {"speed": [5.0, float("nan")], "nodes": [30, 2]},
                       client=client, progress=False)
    assert len(df) == 4
    ok = df["error"].isna()
    assert ok.tolist() == [True, False, False, False]
    assert df.loc[1, "error"] == "ValueError: nodes: needs at least 3 interior nodes, got 2"
    assert "speed: must be a finite number" in df.loc[2, "error"]
    assert np.isnan(df.loc[1, "f1_hz"])


def test_worker_killed_mid_sweep_loses_no_point(client, tmp_path):
    before = set(client.scheduler_info()["workers"])
    df = flowmbd.sweep(sweep_points.dying_point,
                       [{"speed": s, "marker_dir": str(tmp_path)} for s in SPEEDS],
                       client=client, progress=False)
    assert (tmp_path / "died-10.0").exists(), "the worker did die"
    assert df["error"].isna().all(), df["error"].tolist()
    ref = serial()
    pd.testing.assert_frame_equal(df.drop(columns="marker_dir"), ref, check_exact=True)
    # the dead worker was replaced by its nanny (the sweep did not need it to finish)
    client.wait_for_workers(2, timeout=60)
    assert set(client.scheduler_info()["workers"]) != before


def test_default_local_cluster_returns_one_row_per_point():
    df = flowmbd.sweep(sweep_points.string_point, {"speed": [0.0, 20.0]}, progress=False)
    assert len(df) == 2 and df["error"].isna().all()
    assert df["f1_hz"].iloc[1] < df["f1_hz"].iloc[0]  # the axial speed lowers f1 (Ribaric 4.2.3)


def test_reduced_tire_reduced_on_a_worker_is_shipped_to_the_sweep(client):
    # reference: the same points run in this process with a tire reduced here
    from test_tire import TIRE

    fut = client.submit(flowmbd.tire.reduce, TIRE, pure=False)
    grid = [{"speed_kmh": v, "tire": fut} for v in (40.0, 60.0)]
    df = flowmbd.sweep(sweep_points.cleat_point, grid, client=client, progress=False)
    assert df["error"].isna().all(), df["error"].tolist()
    local = flowmbd.tire.reduce(TIRE)
    ref = pd.DataFrame([{"speed_kmh": v, **sweep_points.cleat_point(v, local), "error": None}
                        for v in (40.0, 60.0)])
    pd.testing.assert_frame_equal(df.drop(columns="tire"), ref, check_exact=False, rtol=1e-12)


def _loss_point(torque):
    # a stand-in for a study's summary: nested per-point results and prose
    return {
        "omega_driver": 62.8,
        "meaning": "a long paragraph",
        "points": [{"torque": 0.0, "delta_omega": 0.0}, {"torque": torque, "delta_omega": 0.01 * torque}],
        "analytical": np.array([0.0, 0.004 * torque]),
    }


def test_select_and_explode_flatten_per_point_results():
    # reference: the same values read by hand from the returned dicts
    grid = {"torque": [2.0, 4.0]}
    df = flowmbd.sweep(_loss_point, grid, client=False, progress=False,
                       select={"dw": "points.1.delta_omega", "bechtel": "analytical.1",
                               "ratio": lambda r: r["points"][1]["delta_omega"] / r["analytical"][1]})
    assert "meaning" not in df.columns
    assert list(df["dw"]) == [0.02, 0.04]
    assert list(df["bechtel"]) == pytest.approx([0.008, 0.016])
    assert list(df["ratio"]) == pytest.approx([2.5, 2.5])
    assert df["error"].isna().all()
    rows = flowmbd.sweep(_loss_point, grid, client=False, progress=False, explode="points")
    assert len(rows) == 4
    assert list(rows["points_index"]) == [0, 1, 0, 1]
    # the grid's own "torque" wins over the element's key of the same name
    assert list(rows["delta_omega"]) == [0.0, 0.02, 0.0, 0.04]
    bad = flowmbd.sweep(_loss_point, grid, client=False, progress=False, select={"x": "points.7.torque"})
    assert bad["error"].str.contains("not an index").all()
    with pytest.raises(ValueError, match="select"):
        flowmbd.sweep(_loss_point, grid, client=False, progress=False, select={"x": 3})
