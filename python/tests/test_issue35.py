"""Issue 35: a point that panics is recorded in a sweep, not left hanging; a non-symmetric K
and more modes than the model has are refused; bad arguments of every public function raise
ValueError naming the argument, never TypeError, OverflowError or RecursionError."""

import numpy as np
import pandas as pd
import pytest
import scipy.sparse as sp

import flowmbd


def chain(n):
    """A spring chain fixed at one end: K tridiagonal, M = I (definition)."""
    k = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1], format="csr")
    return sp.identity(n, format="csr"), k


class Panic(BaseException):
    """Like pyo3's PanicException: a BaseException, not an Exception."""


def point(x):
    if x == 2:
        raise Panic("index out of bounds")
    return {"y": 2 * x}


def test_a_panicking_point_is_recorded_like_any_failure():
    df = flowmbd.sweep(point, {"x": [1, 2, 3]}, client=False, progress=False)
    assert list(df["y"].fillna(-1)) == [2, -1, 6]
    assert df["error"][1] == "Panic: index out of bounds"
    assert pd.isna(df["error"][0])


def test_a_non_symmetric_stiffness_is_refused():
    m, k = chain(4)
    k = k.tolil()
    k[0, 1] = -1.5
    with pytest.raises(ValueError, match=r"K`?: not symmetric: entry \((1, 2|2, 1)\)"):
        flowmbd.reduce.craig_bampton(m, k.tocsr(), boundary=[0], modes=1)
    with pytest.raises(ValueError, match="not symmetric"):
        flowmbd.reduce.modes(m, k.tocsr(), count=1)


def test_more_modes_than_free_dofs_are_refused():
    m, k = chain(5)
    with pytest.raises(ValueError, match=r"count: 6 modes asked, but the model has only 4 free DOFs"):
        flowmbd.reduce.modes(m, k, count=6, fixed=[0])
    assert flowmbd.reduce.modes(m, k, count=4, fixed=[0])["eigenvalues"].shape == (4,)


def deep(n):
    d = {}
    for _ in range(n):
        d = {"a": d}
    return d


def circular():
    d = {}
    d["self"] = d
    return d


M, K = chain(4)

BAD_CALLS = [
    ("count", lambda: flowmbd.reduce.modes(M, K, count=float("inf"))),
    ("count", lambda: flowmbd.reduce.modes(M, K, count=float("nan"))),
    ("count", lambda: flowmbd.reduce.modes(M, K, count=2**70)),
    ("count", lambda: flowmbd.reduce.modes(M, K, count="3")),
    ("count", lambda: flowmbd.reduce.modes(M, K, count=[1])),
    ("fixed", lambda: flowmbd.reduce.modes(M, K, count=1, fixed="0,1")),
    ("fixed", lambda: flowmbd.reduce.modes(M, K, count=1, fixed=[{}])),
    ("fixed", lambda: flowmbd.reduce.modes(M, K, count=1, fixed=[2**70])),
    ("M", lambda: flowmbd.reduce.modes("M", K, count=1)),
    ("M", lambda: flowmbd.reduce.modes({"a": 1}, K, count=1)),
    ("M", lambda: flowmbd.reduce.modes(None, K, count=1)),
    ("modes", lambda: flowmbd.reduce.craig_bampton(M, K, boundary=[0], modes=float("inf"))),
    ("boundary", lambda: flowmbd.reduce.craig_bampton(M, K, boundary=[-1], modes=1)),
    ("speed", lambda: flowmbd.string.modes(speed="fast")),
    ("speed", lambda: flowmbd.string.modes(speed=[20.0])),
    ("speed", lambda: flowmbd.string.modes(speed={"v": 1})),
    ("nodes", lambda: flowmbd.string.modes(nodes=float("inf"))),
    ("nodes", lambda: flowmbd.string.modes(nodes=2**80)),
    ("modes", lambda: flowmbd.string.modes(modes="many")),
    ("config", lambda: flowmbd.string.modes(config=deep(5000))),
    ("config", lambda: flowmbd.string.modes(config=circular())),
    ("config", lambda: flowmbd.string.modes(config={"speed": object()})),
    ("omega", lambda: flowmbd.belt.speed_loss(omega="x", torques=[0.0])),
    ("torques", lambda: flowmbd.belt.speed_loss(torques="1,2")),
    ("torques", lambda: flowmbd.belt.speed_loss(torques=5)),
    ("torques[0]", lambda: flowmbd.belt.speed_loss(torques=[None])),
    ("t_end", lambda: flowmbd.belt.ancf(t_end=[1])),
    ("rpm", lambda: flowmbd.belt.fead(rpm=800)),
    ("speed_kmh", lambda: flowmbd.tire.cleat(speed_kmh="fast")),
    ("config", lambda: flowmbd.tire.generate(config=deep(5000))),
]


@pytest.mark.parametrize("name,call", BAD_CALLS, ids=[f"{i}-{n}" for i, (n, _) in enumerate(BAD_CALLS)])
def test_bad_arguments_raise_value_error_naming_them(name, call):
    with pytest.raises(ValueError) as e:
        call()
    assert name in str(e.value), str(e.value)
