"""The result loaders on committed fixtures (a leading-zero hash, a failed run) and on a run."""
import math
import os

import msbench
from conftest import SOURCE_DIR

SWEEP = os.path.join(SOURCE_DIR, "tests/data/python_results/sweep")


def test_load_sweep_keeps_hashes_as_strings_and_failed_runs():
    df = msbench.results.load_sweep(SWEEP)
    assert list(df["id"]) == ["urban-full-s1", "urban-full-s2", "urban-full-s3"]
    assert df.loc[0, "determinism_hash"] == "00a1b2c3d4e5f607"  # leading zeros kept
    assert df.loc[2, "determinism_hash"] == "0123456789012345"  # all digits: still a string
    failed = df[df["status"] == "failed"].iloc[0]
    assert failed["id"] == "urban-full-s2" and math.isnan(failed["area_m2"])
    assert df.loc[0, "area_m2"] == 1250.0


def test_load_run_flattens_metrics():
    df = msbench.results.load_run(os.path.join(SWEEP, "runs", "urban-full-s1"))
    assert len(df) == 1
    assert df.loc[0, "coverage.area_m2"] == 1250.0
    assert df.loc[0, "determinism_hash"] == "00a1b2c3d4e5f607"


def test_load_coverage_of_a_sweep_labels_each_complete_run():
    df = msbench.results.load_coverage(SWEEP)
    assert set(df["id"]) == {"urban-full-s1", "urban-full-s3"}  # the failed run has no curve
    assert set(df["method"]) == {"full"}
    assert df[df["id"] == "urban-full-s1"]["area_m2"].max() == 1250.0
    one = msbench.results.load_coverage(os.path.join(SWEEP, "runs", "urban-full-s3"))
    assert list(one["area_m2"]) == [0.0, 300.0]
