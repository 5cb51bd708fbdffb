"""sweep() on a Dask LocalCluster of two worker processes equals the local run."""

import os

import pandas as pd
import pytest

import shadowlab

distributed = pytest.importorskip("distributed")

# Two views (fence from its own camera and from an orbit) x two techniques x two map sides: 8
# rows, in tasks of 2 rows, so that both workers get work.
SPEC = {"techniques": ["modern.hw", "modern.gems4"], "scenes": ["fence"], "sizes": ["64x48"],
        "shadow_maps": [256, 512], "orbits": [None, [20, 25, 9]], "repeat": 1}

# Columns that are measured times (and their spread, the machine's load and the date of the
# measurement), equal only by chance between two runs.
TIME_COLUMNS = {"frame_ms", "wall_ms", "passes", "pareto_rank", "frame_iqr_ms", "frame_min_ms",
                "spread_large", "load_before", "load_after", "date"}


def error_columns(frame):
    return [c for c in frame.columns
            if c.endswith(("rmse", "max_abs", "share_above_half", "leak_share"))
            or c in ("scored_pixels", "left_out_share", "temporal_change",
                     "reference_temporal_change")]


@pytest.fixture(scope="module")
def cluster():
    # Workers are spawned processes: they import shadowlab from PYTHONPATH like this one.
    assert "PYTHONPATH" in os.environ
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                  host="127.0.0.1", dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        yield client


def test_a_two_worker_sweep_equals_the_local_one(cluster):
    local = shadowlab.sweep(SPEC)
    remote = shadowlab.sweep(SPEC, client=cluster, task_rows=2)  # 4 tasks
    assert len(local) == 8 and (local["status"] == "ok").all()
    assert list(remote.columns) == list(local.columns)
    errors = error_columns(local)
    assert "hard_rmse" in errors and "soft_point_band_rmse" in errors
    # Every error column, exactly: the same renders on the same references in other processes.
    pd.testing.assert_frame_equal(remote[errors], local[errors], check_exact=True)
    same = [c for c in local.columns if c not in TIME_COLUMNS]
    pd.testing.assert_frame_equal(remote[same], local[same], check_exact=True)
    # Both worker processes measured rows: each holds the references of the views it measured.
    views = cluster.run(lambda: shadowlab._REFERENCES.views())
    assert len(views) == 2 and all(n >= 1 for n in views.values()), views
    assert local["orbit"].tolist()[-1] == "20,25,9"


def test_workers_raise_the_same_value_error(cluster):
    with pytest.raises(ValueError, match=r"^unknown technique 'nope'"):
        shadowlab.sweep({"techniques": ["nope"]}, client=cluster)
