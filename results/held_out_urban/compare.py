"""Earned score at 300 s: MonoSpheres (table1_reference's urban configuration) on the fixed urban
(ten seeds, table1_reference at 9a90737: runs/fixed-s*, the running curve of coverage.csv) against held-out
urban worlds (one salt per seed, this build). The running curve is the score before the
collision forfeit; metrics.json's `earned` after it is shown for the held-out runs too."""
import csv
import glob
import json
import os
import statistics
import sys

def at300(d):
    rows = list(csv.DictReader(open(os.path.join(d, "coverage.csv"))))
    last = [r for r in rows if float(r["t_s"]) <= 299.5][-1]
    return float(last["score_earned_m3"]), float(last["area_m2"])

def table(dirs):
    out = []
    for d in dirs:
        m = json.load(open(os.path.join(d, "metrics.json")))
        e, a = at300(d)
        out.append((os.path.basename(d), m["status"], round(m["sim_time_s"]), e, a))
    return out

HERE = os.path.dirname(os.path.abspath(__file__))
HELD = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "runs")
fixed = table(sorted(glob.glob(os.path.join(HERE, "runs", "fixed-s*")), key=lambda p: int(p.rsplit("s", 1)[1])))
held = table(sorted(glob.glob(os.path.join(HELD, "held-s*")), key=lambda p: int(p.rsplit("s", 1)[1])))
for name, rows in (("fixed urban", fixed), ("held-out urban", held)):
    print(f"{name}:")
    for r in rows:
        print(f"  {r[0]}: {r[1]} at {r[2]} s, earned at 299 s {r[3]:.0f} m3, A {r[4]:.0f} m2")
    e = [r[3] for r in rows]
    a = [r[4] for r in rows]
    print(f"  earned: mean {statistics.mean(e):.0f}, sd {statistics.stdev(e):.0f}, range {min(e):.0f}-{max(e):.0f}; "
          f"A: mean {statistics.mean(a):.0f}, range {min(a):.0f}-{max(a):.0f}")
