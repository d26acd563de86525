"""Results as pandas data frames: one run, a sweep, coverage curves (docs/python.md).

Hashes and ids are read as strings (pandas would read an all-digit hash as an integer and drop
its leading zeros); failed runs of a sweep are present, with NaN metrics and their status.
"""
import json
import os

import pandas as pd

# Columns that are names, never numbers.
_STRING_COLUMNS = {"id": str, "determinism_hash": str, "run_status": str, "status": str}


def _flatten(prefix, value, out):
    """metrics.json's nested objects as dotted column names (lists kept as they are)."""
    if isinstance(value, dict):
        for k, v in value.items():
            _flatten(f"{prefix}.{k}" if prefix else k, v, out)
    else:
        out[prefix] = value


def load_run(run_dir):
    """One run directory's metrics.json as a one-row DataFrame with dotted columns
    (coverage.area_m2, frontend_profile.moved_over_0_3_m_share, ...) and its directory."""
    path = os.path.join(run_dir, "metrics.json")
    with open(path, encoding="utf-8") as f:
        metrics = json.load(f)
    row = {}
    _flatten("", metrics, row)
    row["dir"] = os.path.abspath(run_dir)
    frame = pd.DataFrame([row])
    for col in ("determinism_hash", "map_hash", "trajectory_hash", "name", "status"):
        if col in frame:
            frame[col] = frame[col].astype("string")
    return frame


# runs.csv's figures (verified_* since the runs.csv of 2026-11-28, score_earned_m3 since the earned
# score; absent in older sweeps).
_NUMERIC_COLUMNS = ("area_m2", "box_share", "sim_time_s", "wall_time_s", "verified_area_m2", "verified_box_share",
                    "score_earned_m3")


def load_sweep(sweep_dir):
    """A sweep directory's runs.csv: one row per run (failed and pending ones included, their
    metrics NaN), the axis labels as columns, hashes and ids as strings."""
    path = os.path.join(sweep_dir, "runs.csv")
    frame = pd.read_csv(path, dtype=_STRING_COLUMNS, keep_default_na=False, na_values={
        c: [""] for c in _NUMERIC_COLUMNS})
    for col in _NUMERIC_COLUMNS:
        if col in frame:
            frame[col] = pd.to_numeric(frame[col], errors="coerce")
    for col in ("id", "determinism_hash", "status", "run_status"):
        if col in frame:
            frame[col] = frame[col].astype("string")
    frame["dir"] = [os.path.abspath(os.path.join(sweep_dir, "runs", i)) for i in frame["id"]]
    return frame


def load_coverage(path):
    """Coverage over simulated time (coverage.csv) of a run directory, or of every complete run
    of a sweep directory with its id and axis labels as columns."""
    if os.path.exists(os.path.join(path, "coverage.csv")):
        return pd.read_csv(os.path.join(path, "coverage.csv"))
    runs = load_sweep(path)
    labels = [c for c in runs.columns if c not in _NUMERIC_COLUMNS + ("status", "run_status", "determinism_hash",
                                                                       "exit_code", "signal", "dir")]
    parts = []
    for _, run in runs.iterrows():
        csv = os.path.join(run["dir"], "coverage.csv")
        if run["status"] != "complete" or not os.path.exists(csv):
            continue
        c = pd.read_csv(csv)
        for col in labels:
            c[col] = run[col]
        parts.append(c)
    if not parts:
        return pd.DataFrame()
    return pd.concat(parts, ignore_index=True)
