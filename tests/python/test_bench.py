"""bench() and sweep() in this process, against `shadowlab bench`."""

import json

import numpy as np
import pandas as pd
import pytest

import shadowlab
from conftest import read_png  # noqa: F401  (the package's conftest is imported by pytest)

# One scene and technique of the bench at a small window: fence (the only scene it runs; brabec
# would add its claim scenes), modern.hw's sweep of five variants, one timed frame each.
BENCH = dict(scenes="fence", techniques="modern.hw", quick=True, size=(64, 48), repeat=1)
BENCH_CLI = ["--scene", "fence", "--technique", "modern.hw", "--quick", "--size", "64x48",
             "--repeat", "1"]

ERROR_COLUMNS = [f"{ref}_{m}" for ref in ("hard", "soft", "hard_point", "soft_point")
                 for m in ("rmse", "max_abs", "share_above_half", "band_rmse", "band_max_abs",
                           "band_share_above_half", "leak_share")]


@pytest.fixture(scope="module")
def cli_bench(cli, tmp_path_factory):
    """The CLI's rows: its JSON lines by variant, and its CSV."""
    out = tmp_path_factory.mktemp("bench")
    status, stdout, err = cli("bench", *BENCH_CLI, "--out", str(out), "--csv",
                              str(out / "bench.csv"))
    assert status == 0, err
    rows = [json.loads(line) for line in stdout.splitlines() if line.startswith("{")]
    rows = {r["variant"]: r for r in rows if "variant" in r}
    return rows, pd.read_csv(out / "bench.csv")


@pytest.fixture(scope="module")
def python_bench():
    return shadowlab.bench(**BENCH)


def test_bench_has_the_cli_columns_and_rows(cli_bench, python_bench):
    rows, csv = cli_bench
    assert list(python_bench.columns) == list(csv.columns)
    assert sorted(python_bench["variant"]) == sorted(rows)
    assert (python_bench["status"] == "ok").all()
    assert len(python_bench) >= 3, "modern.hw's sweep has a default and its variants"


def test_bench_errors_equal_the_cli_rows(cli_bench, python_bench):
    rows, csv = cli_bench
    for _, row in python_bench.iterrows():
        line = rows[row["variant"]]
        # Full precision: the JSON line's doubles, exactly.
        assert row["hard_rmse"] == line["vs_reference_hard_area"]["rmse"]
        assert row["hard_band_rmse"] == line["vs_reference_hard_area"]["band_rmse"]
        assert row["soft_point_leak_share"] == line["vs_reference_soft_centre"]["leak_share"]
        assert row["scored_pixels"] == line["error"]["scored_pixels"]
        assert row["temporal_change"] == line["temporal_change"]
        # The CSV prints 6 significant digits: the same numbers at its precision.
        printed = csv[csv["variant"] == row["variant"]].iloc[0]
        for column in ERROR_COLUMNS:
            assert row[column] == pytest.approx(printed[column], rel=5e-6, abs=1e-12), column
    assert python_bench["hard_rmse"].gt(0).all()


def test_bench_types():
    frame = shadowlab.bench(**BENCH)
    assert frame["width"].dtype == "Int64" and frame["frame_ms"].dtype == np.float64
    assert frame["params"].dtype == object and frame["precision"].dtype == object


SPEC = {"techniques": ["modern.hw", "modern.pcf"], "scenes": ["fence"], "sizes": ["64x48"],
        "shadow_maps": [256, 512], "filters": [2, 3], "repeat": 1}


@pytest.fixture(scope="module")
def local_sweep():
    return shadowlab.sweep(SPEC)


def test_sweep_expands_the_axes_each_technique_reads(local_sweep):
    # modern.hw reads --shadow-map only (2 rows); modern.pcf --shadow-map and --filter (4).
    assert list(local_sweep["technique"]) == ["modern.hw"] * 2 + ["modern.pcf"] * 4
    assert list(local_sweep["variant"][:3]) == ["shadow-map=256", "shadow-map=512",
                                                "shadow-map=256 filter=2"]
    assert (local_sweep["status"] == "ok").all()
    assert list(shadowlab.sweep_rows(SPEC)["variant"]) == list(local_sweep["variant"])
    assert local_sweep["pareto_rank"].min() == 1
    assert (local_sweep["orbit"] == "").all()


def test_a_sweep_row_equals_the_bench_row_of_the_same_variant(python_bench, local_sweep):
    # The bench's "shadow-map=256" variant of modern.hw on fence at 64x48 is the sweep's first
    # row: the same measurement code on the same references.
    bench_row = python_bench[python_bench["variant"] == "shadow-map=256"].iloc[0]
    sweep_row = local_sweep.iloc[0]
    for column in ERROR_COLUMNS + ["scored_pixels", "temporal_change",
                                   "reference_temporal_change"]:
        assert sweep_row[column] == bench_row[column], column


def test_a_value_one_technique_refuses_is_that_rows_status(cli, tmp_path):
    # Fast PCF packs 2x2 neighbours (and 4x4 in phases): --filter 3 is refused by the technique,
    # which the sweep records as the bench does, with render's message.
    spec = {"techniques": ["modern.fast-pcf"], "scenes": ["fence"], "sizes": ["64x48"],
            "filters": [2, 3], "repeat": 1}
    rows = shadowlab.sweep(spec)
    assert list(rows["status"])[0] == "ok"
    status, _, err = cli("render", "--scene", "fence", "--technique", "modern.fast-pcf",
                         "--size", "64x48", "--filter", "3", "--out", str(tmp_path / "x.png"))
    assert status == 2
    assert rows["status"].iloc[1] == "invalid: " + err.strip()[len("shadowlab: "):]
    assert pd.isna(rows["pareto_rank"].iloc[1])


def test_unmeasured_cells_are_empty_not_zero():
    # A view measured without reference.soft: its soft columns are NaN (empty cells of the CSV),
    # not 0; a row that did not run (fast PCF refuses --filter 3) has no time and no error.
    spec = {"techniques": ["modern.fast-pcf"], "scenes": ["fence"], "sizes": ["64x48"],
            "filters": [2, 3], "repeat": 1, "soft_reference": False, "temporal": False}
    rows = shadowlab.sweep(spec)
    ran, refused = rows.iloc[0], rows.iloc[1]
    assert ran["status"] == "ok" and ran["hard_rmse"] > 0
    for column in ("soft_rmse", "soft_band_rmse", "soft_point_rmse", "soft_point_leak_share"):
        assert pd.isna(ran[column]), column
    assert refused["status"] != "ok"
    for column in ("frame_ms", "wall_ms", "hard_rmse", "hard_point_rmse", "scored_pixels"):
        assert pd.isna(refused[column]), column


def test_sweep_orbits_and_params():
    spec = {"techniques": ["modern.csm"], "scenes": ["fence"], "sizes": [[64, 48]],
            "params": {"order": [4, 8]}, "orbits": [None, "20,25,9"], "repeat": 1,
            "soft_reference": False, "temporal": False}
    rows = shadowlab.sweep_rows(spec)
    assert list(rows["variant"]) == ["order=4", "order=8"] * 2
    assert list(rows["orbit"].fillna("")) == ["", "", "20,25,9", "20,25,9"]


@pytest.mark.parametrize("spec, message", [
    ({}, r'^sweep: "techniques" is required$'),
    ({"techniques": ["nope"]}, r"^unknown technique 'nope'"),
    ({"techniques": ["modern.hw"], "colour": 1}, r'^sweep: unknown key "colour"'),
    ({"techniques": ["modern.hw"], "sizes": ["64by48"]}, r"^--size must look like 800x600"),
    ({"techniques": ["modern.hw"], "params": {"order": [4]}},
     r"^sweep: \"params\": no technique of the sweep has a parameter 'order'"),
    ({"techniques": ["modern.hw"], "orbits": [[0, 95, 5]]}, r"^--orbit elevation must lie"),
    ({"techniques": ["modern.hw"], "repeat": 0}, r'^sweep: "repeat" must be a whole number'),
    ({"techniques": ["modern.hw"], "scenes": ["no-such-scene"]}, r"no-such-scene"),
])
def test_a_bad_spec_is_a_value_error_before_anything_runs(spec, message):
    with pytest.raises(ValueError, match=message):
        shadowlab.sweep(spec)


def test_merge_recomputes_ranks_over_every_frame(local_sweep):
    # A copy of the sweep a million times faster (every copy faster than every original, the
    # same errors): each copy dominates its original and no original dominates a copy, so the
    # copies take the originals' ranks and every original drops behind its copy.
    faster = local_sweep.copy()
    faster["frame_ms"] = faster["frame_ms"] / 1e6
    merged = shadowlab.merge(local_sweep, faster)
    n = len(local_sweep)
    assert len(merged) == 2 * n
    assert list(merged["pareto_rank"][n:]) == list(local_sweep["pareto_rank"])
    for before, after in zip(local_sweep["pareto_rank"], merged["pareto_rank"][:n]):
        assert after > before
    assert (local_sweep["frame_ms"] == merged["frame_ms"][:n]).all(), "the inputs are kept"
    with pytest.raises(ValueError):
        shadowlab.merge()
