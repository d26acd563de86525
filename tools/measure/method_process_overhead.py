#!/usr/bin/python3
"""The cost of running a Python method in its own process (docs/performance.md): the hover-turn
twin in urban, alternating in-process and own-process runs of the same mission.

    PYTHONPATH=build/python /usr/bin/python3 tools/measure/method_process_overhead.py \\
        [--duration 300] [--reps 2] [KEY=VALUE ...]      # extra --set overrides

Prints each run's wall time, hash and where the method ran; the hashes must agree."""
import argparse
import os
import sys
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "../.."))
sys.path.insert(0, os.path.join(ROOT, "examples/python"))
import hover_turn  # noqa: E402
import msbench  # noqa: E402

CPP = os.path.join(ROOT, "examples/hover_turn.yaml")
PY = os.path.join(ROOT, "examples/hover_turn_python.yaml")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=300.0)
    ap.add_argument("--reps", type=int, default=2)
    ap.add_argument("sets", nargs="*")
    a = ap.parse_args()
    sets = [f"duration_s={a.duration:g}"] + a.sets
    modes = (("in-process", lambda: msbench.Mission(msbench.Scenario.load(CPP, set=sets), method=hover_turn.factory)),
             ("own process", lambda: msbench.Mission(msbench.Scenario.load(PY, set=sets))))
    walls = {name: [] for name, _ in modes}
    for _ in range(a.reps):
        for name, make in modes:
            t0 = time.perf_counter()
            m = make()
            m.run(progress=False)
            r = m.result()
            walls[name].append(time.perf_counter() - t0)
            print(f"{name}: wall {walls[name][-1]:.1f} s, hash {m.hash}, {r['method_confinement']}", flush=True)
    mean = {k: sum(v) / len(v) for k, v in walls.items()}
    print(f"ratio of means (own process / in-process): {mean['own process'] / mean['in-process']:.2f}")


if __name__ == "__main__":
    main()
