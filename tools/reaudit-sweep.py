#!/usr/bin/python3
"""Re-takes the collision audits of a published sweep (docs/sweeps.md, "Re-auditing published runs").

    tools/reaudit-sweep.py results/table1 [--jobs 2] [--work DIR] [--dry-run]

The collision audit is a check beside the loop: it reads the run, never steers it. So every run of
DEST/runs/ that ended in a collision is run again from its effective configuration
(`msbench run runs/ID/config.yaml`) with the binary built here, its determinism, trajectory and map
hashes are compared with the published ones, and only when all three are equal is the published
metrics.json's `collision.audit` block replaced, as text, by the block the new run wrote (the rest
of the record stays byte for byte as published, but for its seal `record_digest`, which is removed). A run whose hashes differ is left as it was and
reported. Prints a table (run, object, part, cause before → after, SLAM points on the part, nearest
map point) and writes it, with the binary's revision, to DEST/reaudit.csv. A binary built from
uncommitted changes is refused (--allow-dirty to accept it). Exit 1 if any run differed, failed
or was refused. Needs msbench in build/bin (or MSBENCH).
"""
import argparse
import concurrent.futures
import csv
import json
import os
import pathlib
import re
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent
HASHES = ("determinism_hash", "trajectory_hash", "map_hash")


def audit_block(text):
    """(start, end) of the `"audit": {...}` object inside `"collision"` (a flat object)."""
    start = text.index('    "audit": {')
    end = text.index("\n    }", start) + len("\n    }")
    return start, end


def rerun(msbench, run_dir, work):
    """Runs the published run again; returns (new metrics text, error or None)."""
    out = work / run_dir.name
    cmd = [msbench, "run", str(run_dir / "config.yaml"), "--out", str(out), "--quiet", "--overwrite"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    metrics = out / "metrics.json"
    if not metrics.exists():
        return None, f"exit {p.returncode}: {p.stderr.strip()[-300:]}"
    return metrics.read_text(), None


def row_of(run_id, old, new, status):
    c_old, c_new = old["collision"], (new or old)["collision"]
    a_old, a_new = c_old["audit"], c_new["audit"]
    return {
        "run": run_id, "t_s": c_old["t_s"], "object": c_old["object"], "part": c_old["world_geom"],
        "cause_before": a_old["cause"], "cause": a_new["cause"],
        "slam_points_on_part": a_new["slam_points_on_part"], "slam_points_on_object": a_new["slam_points_on_object"],
        "map_points_on_object": a_new["map_points_on_object"],
        "nearest_map_point_m": round(a_new["nearest_map_point_m"], 3), "vio_drift_m": round(a_new["vio_drift_m"], 2),
        "hashes": status,
    }


def reaudit(msbench, run_dir, work, dry_run, allow_dirty):
    path = run_dir / "metrics.json"
    text = path.read_text()
    old = json.loads(text)
    new_text, error = rerun(msbench, run_dir, work)
    if error:
        return row_of(run_dir.name, old, None, "failed: " + error)
    new = json.loads(new_text)
    revision = new["versions"]["git_revision"]
    if revision.endswith("-dirty") and not allow_dirty:
        return row_of(run_dir.name, old, None, f"refused: the binary was built from uncommitted changes ({revision})")
    differ = [h for h in HASHES if new.get(h) != old.get(h)]
    if differ or new.get("collision") is None:
        return row_of(run_dir.name, old, None, "differ: " + ", ".join(differ or ["no collision"]))
    s, e = audit_block(text)
    ns, ne = audit_block(new_text)
    if not dry_run:
        tmp = path.with_suffix(".json.tmp")
        edited = text[:s] + new_text[ns:ne] + text[e:]
        # A sealed record (record_digest) is no longer as msbench wrote it: the seal goes, and
        # the record reads as one from before the seal (its hashes were checked equal above).
        edited = re.sub(r'\n\s*"record_digest": "[^"]*",', "", edited)
        tmp.write_text(edited)
        json.loads(tmp.read_text())  # still one JSON document
        os.replace(tmp, path)
    row = row_of(run_dir.name, old, new, "equal")
    row["revision"] = new["versions"]["git_revision"]
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dest", type=pathlib.Path, help="published sweep (results/NAME)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--work", type=pathlib.Path, default=None, help="where the runs go (default: a temp dir)")
    ap.add_argument("--dry-run", action="store_true", help="run and compare, change nothing")
    ap.add_argument("--allow-dirty", action="store_true",
                    help="accept a binary built from uncommitted changes (refused by default: the audit names its build)")
    args = ap.parse_args()
    msbench = os.environ.get("MSBENCH", str(HERE.parent / "build" / "bin" / "msbench"))
    if not os.access(msbench, os.X_OK):
        sys.exit(f"{sys.argv[0]}: {msbench} not found (build it first)")
    runs = sorted(d for d in (args.dest / "runs").iterdir()
                  if (d / "metrics.json").exists() and json.loads((d / "metrics.json").read_text())["status"] == "collided")
    work = args.work or pathlib.Path(subprocess.check_output(["mktemp", "-d", "/tmp/msb_reaudit.XXXXXX"], text=True).strip())
    work.mkdir(parents=True, exist_ok=True)
    print(f"{args.dest}: {len(runs)} collided runs, re-run in {work}", file=sys.stderr)
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        rows = list(pool.map(lambda d: reaudit(msbench, d, work, args.dry_run, args.allow_dirty), runs))
    revision = sorted({r.get("revision", "?") for r in rows})
    for r in rows:
        r.pop("revision", None)
    if rows and not args.dry_run:
        with open(args.dest / "reaudit.csv", "w", newline="") as f:
            f.write(f"# collision audits re-taken by tools/reaudit-sweep.py with the build of {', '.join(revision)}\n")
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    cols = ["run", "t_s", "part", "cause_before", "cause", "slam_points_on_part", "nearest_map_point_m", "hashes"]
    print("| " + " | ".join(cols) + " |\n|" + " --- |" * len(cols))
    for r in rows:
        print("| " + " | ".join(str(r[c]) for c in cols) + " |")
    sys.exit(0 if all(r["hashes"] == "equal" for r in rows) else 1)


if __name__ == "__main__":
    main()
