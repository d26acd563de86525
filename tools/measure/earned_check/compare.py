"""The earned score on Table I's committed runs (issue 71): a sweep of table1_seeds12.yaml (SWEEP_DIR;
published as results/earned_table1) against results/table1's records — the hash of each must be the
committed one (scoring is beside the loop), and per world the order of MonoSpheres and Grid under
the earned score (with and without the collision forfeit) is printed beside the paper's A.
    python3 tools/measure/earned_check/compare.py SWEEP_DIR [results/table1]"""
import csv
import json
import os
import sys

sweep = sys.argv[1]
table = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(__file__), "../../../results/table1")
committed = {r["id"]: r for r in csv.DictReader(open(os.path.join(table, "runs.csv")))}
rows, bad = {}, 0
print(f"{'run':26s} {'status':9s} {'A m2':>8s} {'earned m3':>10s} {'before forfeit':>14s} {'share':>6s}  hash")
for r in csv.DictReader(open(os.path.join(sweep, "runs.csv"))):
    if r["status"] != "complete":
        continue
    m = json.load(open(os.path.join(sweep, "runs", r["id"], "metrics.json")))
    same = m["determinism_hash"] == committed[r["id"]]["determinism_hash"]
    bad += not same
    s = m["score"]
    print(f"{r['id']:26s} {m['status']:9s} {m['coverage']['area_m2']:8.0f} {s['earned']:10.0f} "
          f"{s['before_forfeit']:14.0f} {s['earned_share']:6.3f}  {'= committed' if same else 'DIFFERS'}")
    rows.setdefault((r["world"], r["method"]), []).append((m["coverage"]["area_m2"], s["earned"], s["before_forfeit"]))
print()
print(f"{'world':9s} {'method':12s} {'n':>2s} {'mean A':>8s} {'mean earned':>12s} {'before forfeit':>14s}")
for (world, method), v in sorted(rows.items()):
    n = len(v)
    print(f"{world:9s} {method:12s} {n:2d} {sum(x[0] for x in v) / n:8.0f} {sum(x[1] for x in v) / n:12.0f} "
          f"{sum(x[2] for x in v) / n:14.0f}")
for world in sorted({w for w, _ in rows}):
    ms, grid = rows.get((world, "monospheres")), rows.get((world, "grid"))
    if ms and grid:
        mean = lambda v, k: sum(x[k] for x in v) / len(v)
        print(f"{world}: MonoSpheres {'>' if mean(ms, 1) > mean(grid, 1) else '<='} Grid on the earned score "
              f"(A: {'>' if mean(ms, 0) > mean(grid, 0) else '<='}; before forfeit: "
              f"{'>' if mean(ms, 2) > mean(grid, 2) else '<='})")
print(f"hashes: {bad} differ from the committed runs")
