"""A keyed table's resume notice says what it found (user38: a grooves --loss-speed run
stopped before its first geometry was resumed with 'starting afresh: the table there is not
this run's (other arguments or case ...)', its arguments unchanged)."""

import pytest

from webfem.sweeps.keyed import run_points

COLUMNS = ("x", "y", "converged")


def _run(path, sig, solve, told):
    return run_points(path, sig, COLUMNS, ("x",), [(1.0,), (2.0,)], solve, notice=told.append)


def test_a_table_of_the_same_run_without_rows_is_resumed_not_replaced(tmp_path):
    path = tmp_path / "t.csv"

    def stop(n):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        _run(path, {"model": "m", "parameter": "p", "a": 1}, stop, [])
    told = []
    rows = _run(path, {"model": "m", "parameter": "p", "a": 1}, lambda n: {"x": n + 1.0, "y": 2.0 * n, "converged": True}, told)
    assert [r["y"] for r in rows] == [0.0, 2.0]
    assert told and "resuming: none of its 2 points kept (the earlier run was stopped " \
        "before any was solved)" in told[0]
    # another run's table is still replaced, and says so
    told = []
    _run(path, {"model": "m", "parameter": "p", "a": 2}, lambda n: {"x": n + 1.0, "y": 0.0, "converged": True}, told)
    assert "starting afresh" in told[0]


def test_a_table_of_failed_rows_says_they_are_solved_again(tmp_path):
    path = tmp_path / "t.csv"
    _run(path, {"model": "m", "parameter": "p", "a": 1}, lambda n: {"x": n + 1.0, "y": None, "converged": False}, [])
    told = []
    _run(path, {"model": "m", "parameter": "p", "a": 1}, lambda n: {"x": n + 1.0, "y": 1.0, "converged": True}, told)
    assert "its 2 rows did not converge: solved again" in told[0]
