"""Results as objects (issue 39 item 5): every study returns a flowmbd.Result, a dict whose
``to_dataframe()`` tabulates its per-point records. Reference: the CLI's own table of the same
run, ``speed_loss.csv`` (one row per load torque), and the per-pulley records of summary.json."""

import csv

import numpy as np
import pytest

import flowmbd

pd = pytest.importorskip("pandas")


def test_speed_loss_points_match_the_cli_csv(cli, tmp_path):
    torques = [0.0, 10.0]
    r = flowmbd.belt.speed_loss(omega=62.8, torques=torques)
    assert isinstance(r, flowmbd.Result) and isinstance(r, dict)
    df = r.to_dataframe()
    assert r.records() == "points"
    assert list(df["points_index"]) == [0, 1]
    np.testing.assert_allclose(df["torque"], torques)
    code, summary, err = cli("belt", "speed-loss", "--omega", "62.8", "--torques", "0,10")
    assert code == 0, err
    out = tmp_path / "belt"  # the fixture's --out
    with open(out / "speed_loss.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == len(df)
    # the CLI writes 11 significant digits
    np.testing.assert_allclose(
        df["delta_omega"], [float(x["delta_omega_rad_per_s"]) for x in rows], rtol=1e-9, atol=1e-12
    )
    np.testing.assert_allclose(df["torque"], [float(x["torque_N_m"]) for x in rows])
    # nested lists and dicts are not columns; prose is not a column either
    assert "pulleys" not in df.columns and "hub_loads" not in df.columns


def test_explode_gives_one_row_per_pulley():
    r = flowmbd.belt.speed_loss(omega=62.8, torques=[0.0, 10.0])
    df = r.to_dataframe(explode="pulleys")
    n = sum(len(p["pulleys"]) for p in r["points"])
    assert len(df) == n == 4
    for _, row in df.iterrows():
        p = r["points"][row["points_index"]]["pulleys"][row["pulleys_index"]]
        assert row["name"] == p["name"]
        assert row["torque_n_m"] == p["torque_n_m"]
        # the point's own scalar fields ride along
        assert row["torque"] == r["points"][row["points_index"]]["torque"]


def test_bad_record_paths_name_the_path():
    r = flowmbd.belt.speed_loss(omega=62.8, torques=[0.0])
    with pytest.raises(KeyError, match="nothing"):
        r.to_dataframe("nothing")
    with pytest.raises(KeyError, match="not a list of records"):
        r.to_dataframe("omega_driver")
