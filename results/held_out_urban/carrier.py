#!/usr/bin/python3
"""Does a method that ships urban's truth still win on held-out urbans? (docs/worlds.md,
"Held-out worlds".) MonoSpheres flies urban (urban_short.yaml, oracle front end, blank renderer);
the truth carrier of the tests (tests/tools/python/held_out/carrier.py) replays its commands and
declares the truth's free space in sight. It flies the fixed urban, a held-out urban that mirrors
and one that does not; `aware` is the same carrier given the box it memorised, which undoes a
mirror (a mirrored world's box is mirrored too). Printed: earned, falsely free (m³), run status.
  python3 results/held_out_urban/carrier.py OUT [DURATION_S]   (PYTHONPATH: build/python)
"""
import glob
import json
import os
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.normpath(os.path.join(HERE, "../.."))
MSBENCH = os.environ.get("MSBENCH_BIN", os.path.join(SRC, "build/bin/msbench"))
URBAN = os.path.join(SRC, "scenarios/missions/urban_short.yaml")
SALTS = {"mirrored": "held-out-test-salt-1-0123456789", "not mirrored": "search-salt-2-0123456789"}


def run(scenario, out, duration, salt=None):
    env = {k: v for k, v in os.environ.items() if not k.startswith("MSBENCH_WORLD_SALT")}
    sets = ["camera_stream.renderer=blank", "perception.source=oracle", f"duration_s={duration}"]
    if salt:
        env["MSBENCH_WORLD_SALT"], sets = salt, sets + ["held_out=true"]
    args = sum([["--set", s] for s in sets], [])
    subprocess.run([MSBENCH, "run", scenario, "--quiet", "--out", out] + args, env=env, check=True)
    return json.load(open(os.path.join(out, "metrics.json")))


def carrier(out, honest, aware):
    """The carrier's folder: its code, MonoSpheres' commands, urban's truth (and box if aware)."""
    d = os.path.join(out, "carrier_aware" if aware else "carrier")
    shutil.copytree(os.path.join(SRC, "tests/tools/python/held_out"), d)
    traj = np.loadtxt(os.path.join(honest, "trajectory.csv"), delimiter=",", skiprows=1)
    np.savetxt(os.path.join(d, "route.csv"), traj[:, [0, 15, 16, 17, 18]], delimiter=",")
    shutil.copy(truth_of(), os.path.join(d, "shapes.csv"))
    if aware:
        box = json.load(open(os.path.join(honest, "metrics.json")))["coverage"]["exploration_box"]
        np.savetxt(os.path.join(d, "box.csv"), [box["min"] + box["max"]], delimiter=",")
    scenario = d + ".yaml"
    with open(scenario, "w") as f:
        f.write(f"base: base\nworld: urban\nmethod: {{type: python, entry: 'carrier:Carrier', path: {d}}}\n")
    return scenario


def truth_of():
    """urban's shapes.csv in the world cache (the world the honest run flew)."""
    from msbench._msbench import worlds_dir
    cache = os.environ.get("MSBENCH_CACHE_DIR") or os.path.join(worlds_dir, ".cache")
    return sorted(glob.glob(os.path.join(cache, "urban-s1-*", "shapes.csv")), key=os.path.getmtime)[-1]


def main():
    out = sys.argv[1]
    duration = int(sys.argv[2]) if len(sys.argv) > 2 else 40
    os.makedirs(out)
    honest = os.path.join(out, "honest")
    rows = [("MonoSpheres", "fixed", run(URBAN, honest, duration))]
    for kind, salt in SALTS.items():
        rows.append(("MonoSpheres", kind, run(URBAN, os.path.join(out, "honest " + kind), duration, salt)))
    for aware in (False, True):
        scenario = carrier(out, honest, aware)
        name = "carrier, box-aware" if aware else "carrier"
        rows.append((name, "fixed", run(scenario, os.path.join(out, name + " fixed"), duration)))
        for kind, salt in SALTS.items():
            rows.append((name, kind, run(scenario, os.path.join(out, f"{name} {kind}"), duration, salt)))
    print(f"urban, {duration} s, oracle front end")
    for who, world, m in rows:
        s = m["score"]
        print(f"  {who:20s} {world:13s} earned {s['earned']:8.1f}  falsely free {s['falsely_free_m3']:6.1f}  {m['status']}")


if __name__ == "__main__":
    main()
