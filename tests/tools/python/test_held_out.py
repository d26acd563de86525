"""Held-out worlds (docs/worlds.md, "Held-out worlds"): `held_out: true` draws the world with the
evaluator's salt; without one nothing runs; the record carries the salt's commitment, never the
salt; and a method that carries the repository's truth meets a world it does not fit."""
import glob
import json
import os
import shutil
import subprocess

import numpy as np

import msbench
from conftest import FAST, MSBENCH_BIN, SOURCE_DIR

URBAN = os.path.join(SOURCE_DIR, "scenarios/missions/urban_short.yaml")
SALT = "held-out-test-salt-1-0123456789"  # one that mirrors urban (world_salt_test.cc checks both kinds)


def run(scenario, out, sets=(), salt=None, duration=40):
    env = {k: v for k, v in os.environ.items() if not k.startswith("MSBENCH_WORLD_SALT")}
    if salt is not None:
        env["MSBENCH_WORLD_SALT"] = salt
    args = sum([["--set", s] for s in FAST + [f"duration_s={duration}"] + list(sets)], [])
    return subprocess.run([MSBENCH_BIN, "run", str(scenario), "--quiet", "--out", str(out)] + args,
                          capture_output=True, text=True, env=env, timeout=600)


def metrics(out):
    return json.loads((out / "metrics.json").read_text())


def test_a_held_out_run_needs_a_salt_and_records_only_its_commitment(tmp_path):
    for salt, why in ((None, "MSBENCH_WORLD_SALT"), ("", "MSBENCH_WORLD_SALT"), ("short", "at least 16")):
        r = run(URBAN, tmp_path / "none", ["held_out=true"], salt, duration=5)
        assert r.returncode == 2 and "held_out" in r.stderr and why in r.stderr, r.stderr
        assert not (tmp_path / "none").exists()
    a, b, c = (run(URBAN, tmp_path / n, ["held_out=true"], s, duration=5)
               for n, s in (("a", SALT), ("b", SALT), ("c", "another-salt-0123456789")))
    assert a.returncode == b.returncode == c.returncode == 0, a.stderr + c.stderr
    ma, mb, mc = metrics(tmp_path / "a"), metrics(tmp_path / "b"), metrics(tmp_path / "c")
    assert ma["determinism_hash"] == mb["determinism_hash"] != mc["determinism_hash"]
    assert ma["world_salt_commitment"] == mb["world_salt_commitment"] != mc["world_salt_commitment"]
    for f in (tmp_path / "a").rglob("*"):
        if f.is_file():
            assert SALT.encode() not in f.read_bytes(), f
    assert "held_out: true" in (tmp_path / "a" / "config.yaml").read_text()


def test_a_method_carrying_the_repositorys_truth_meets_a_world_it_does_not_fit(tmp_path):
    # MonoSpheres flies urban; the carrier memorises its commands and urban's truth (shapes.csv
    # of the world cache) and declares the truth's free space in sight along that route.
    honest = tmp_path / "honest"
    assert run(URBAN, honest).returncode == 0
    method = tmp_path / "carrier"
    shutil.copytree(os.path.join(SOURCE_DIR, "tests/tools/python/held_out"), method)
    traj = np.loadtxt(honest / "trajectory.csv", delimiter=",", skiprows=1)
    route = traj[:, [0, 15, 16, 17, 18]]  # t, ref_x, ref_y, ref_z, ref_yaw: what the honest run commanded
    np.savetxt(method / "route.csv", route, delimiter=",")
    from msbench._msbench import worlds_dir
    cache = os.environ.get("MSBENCH_CACHE_DIR") or os.path.join(worlds_dir, ".cache")
    shapes = sorted(glob.glob(os.path.join(cache, "urban-s1-*", "shapes.csv")), key=os.path.getmtime)[-1]
    shutil.copy(shapes, method / "shapes.csv")
    scenario = tmp_path / "carrier.yaml"
    scenario.write_text(f"base: {os.path.join(SOURCE_DIR, 'scenarios/missions/base.yaml')}\nworld: urban\n"
                        f"method: {{type: python, entry: 'carrier:Carrier', path: {method}}}\n")
    fixed, held, honest_held = tmp_path / "fixed", tmp_path / "held", tmp_path / "honest_held"
    assert run(scenario, fixed).returncode == 0
    assert run(scenario, held, ["held_out=true"], SALT).returncode == 0
    assert run(URBAN, honest_held, ["held_out=true"], SALT).returncode == 0
    so, sf, sh, soh = (metrics(d)["score"] for d in (honest, fixed, held, honest_held))
    print("honest:", so, "\ncarrier on urban:", sf, "\ncarrier on held-out urban:", sh, "\nhonest held out:", soh)
    # On the world it carries, nothing it declares is an obstacle and it outscores the run whose
    # route it flies; on the held-out world its truth declares obstacles free and misses what is
    # free: it earns less than where it fits, and less than MonoSpheres flying that world.
    assert sf["falsely_free_m3"] == 0 and sf["earned"] > so["earned"]
    assert sh["falsely_free_m3"] > 10 and sh["earned"] < sf["earned"] and sh["earned"] < soh["earned"]
