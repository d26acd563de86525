#!/usr/bin/env python3
"""The tables of docs/compute.md from two sweep directories (issue 82):

    compute_tables.py reference COMPUTE_REFERENCE_DIR TABLE1_REFERENCE_DIR
        urban under the published configuration with the reference compute model, beside the same
        runs without compute (table1_reference.yaml, same ids) and the paper: mean A, box share,
        t50/t90, collisions per variant.
    compute_tables.py charged COMPUTE_CHARGED_DIR
        each method free and charged: earned score (a collision keeps min(score, 0)), A, and the
        charged latencies per stage (median, p95 of the runs' medians and p95s).

Reads each run's metrics.json and coverage.csv; prints Markdown."""
import csv
import json
import os
import statistics as st
import sys

PAPER = {"monospheres": 4919, "no_fff": 2470, "no_dbof": 2308, "no_ovde": 747, "no_vpb": 3697}


def runs(d):
    out = {}
    for rid in sorted(os.listdir(os.path.join(d, "runs"))):
        f = os.path.join(d, "runs", rid, "metrics.json")
        if not os.path.exists(f):
            continue
        m = json.load(open(f))
        if "coverage" not in m:
            continue
        with open(os.path.join(d, "runs", rid, "coverage.csv")) as c:
            m["_curve"] = [(float(r["t_s"]), float(r["box_share"])) for r in csv.DictReader(c)]
        out[rid] = m
    return out


def t_share(curve, share):
    for t, s in curve:
        if s >= share:
            return t
    return None


def mean(xs):
    xs = [x for x in xs if x is not None]
    return (st.mean(xs), len(xs)) if xs else (None, 0)


def fmt(v, n=None, digits=0):
    if v is None:
        return "—"
    return f"{v:.{digits}f}" + (f" ({n})" if n is not None else "")


def reference(cdir, fdir):
    comp, free = runs(cdir), runs(fdir)
    print("| variant | runs | mean A, modelled (m²) | mean A, no compute, same seeds | paper | box share | "
          "t50 / t90 (s), modelled | t50 / t90 (s), no compute | collisions modelled / no compute | "
          "map Hz, map s, plan s |")
    print("| --- " * 10 + "|")
    for variant in PAPER:
        ids = sorted((i for i in comp if i.split("-")[1] == variant), key=lambda i: int(i.rsplit("s", 1)[1]))
        if not ids:
            continue
        pairs = [free.get(i) for i in ids]
        a = [comp[i]["coverage"]["area_m2"] for i in ids]
        af = [p["coverage"]["area_m2"] for p in pairs if p]
        box = [comp[i]["coverage"]["box_share"] for i in ids]
        t50 = mean([t_share(comp[i]["_curve"], 0.5) for i in ids])
        t90 = mean([t_share(comp[i]["_curve"], 0.9) for i in ids])
        f50 = mean([t_share(p["_curve"], 0.5) for p in pairs if p])
        f90 = mean([t_share(p["_curve"], 0.9) for p in pairs if p])
        crash = sum(comp[i]["status"] == "collided" for i in ids)
        crash_f = sum(p["status"] == "collided" for p in pairs if p)
        t = [comp[i]["timing"] for i in ids]
        rate = st.mean(x["map"]["rate_hz"] for x in t)
        ml = st.mean(x["map"]["latency_mean_s"] for x in t)
        pl = st.mean(x["plan"]["latency_mean_s"] for x in t)
        print(f"| {variant} | {len(ids)} | {st.mean(a):.0f} | {fmt(*mean(af))} | {PAPER[variant]} | "
              f"{st.mean(box):.2f} | {fmt(t50[0])} ({t50[1]}) / {fmt(t90[0])} ({t90[1]}) | "
              f"{fmt(f50[0])} ({f50[1]}) / {fmt(f90[0])} ({f90[1]}) | {crash}/{len(ids)} / {crash_f}/{len(af)} | "
              f"{rate:.2f}, {ml:.3f}, {pl:.3f} |")


def charged(d):
    rs = runs(d)
    groups = {}
    for rid, m in rs.items():
        method, mode, _ = rid.rsplit("-", 2)
        sc = m.get("score") or {}
        earned = sc.get("earned")
        if m["status"] == "collided" and sc.get("before_forfeit") is not None:
            earned = min(sc["before_forfeit"], 0.0)
        groups.setdefault(method, {}).setdefault(mode, []).append((earned, m))
    print("| method | earned, free (m³) | earned, charged (m³) | A free / charged (m²) | map latency median / p95 (ms) "
          "| plan latency median / p95 (ms) | machine factor |")
    print("| --- " * 7 + "|")
    order = sorted(groups, key=lambda k: -st.mean(e for e, _ in groups[k].get("charged", [(0, None)])))
    for method in order:
        g = groups[method]
        if not g.get("free") or not g.get("charged"):
            continue  # not both modes yet
        fe = [e for e, _ in g.get("free", [])]
        ce = [e for e, _ in g.get("charged", [])]
        fa = [m["coverage"]["area_m2"] for _, m in g.get("free", [])]
        ca = [m["coverage"]["area_m2"] for _, m in g.get("charged", [])]
        t = [m["timing"] for _, m in g.get("charged", [])]
        lat = lambda s, k: st.median(1000 * x[s][k] for x in t) if t else None
        fac = [x["machine_factor"] for x in t]
        print(f"| {method} | {st.mean(fe):.0f} {[round(x) for x in fe]} | {st.mean(ce):.0f} {[round(x) for x in ce]} | "
              f"{st.mean(fa):.0f} / {st.mean(ca):.0f} | {lat('map', 'latency_median_s'):.0f} / "
              f"{lat('map', 'latency_p95_s'):.0f} | {lat('plan', 'latency_median_s'):.0f} / "
              f"{lat('plan', 'latency_p95_s'):.0f} | {min(fac):.3f}–{max(fac):.3f} |")


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "reference":
        reference(sys.argv[2], sys.argv[3])
    elif len(sys.argv) == 3 and sys.argv[1] == "charged":
        charged(sys.argv[2])
    else:
        sys.exit(__doc__)
