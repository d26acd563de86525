"""The module: scenario errors, the effective configuration, stepping with frame views, the same
hash as `msbench run` (twice, in a spawned process, beside a busy thread), writing, Ctrl-C."""
import multiprocessing
import os
import pathlib
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import msbench
from conftest import MSBENCH_BIN, SCENARIO, SOURCE_DIR, fast_sets


def run_hash(sets):
    """The hash of a mission run to its end from Python."""
    m = msbench.Mission(msbench.Scenario.load(SCENARIO, set=sets))
    m.run(progress=False)
    return m.hash


def test_errors_name_file_key_and_reason():
    with pytest.raises(msbench.ConfigError, match=r"urban_short.yaml.*method\.planner\.nope.*unknown key"):
        msbench.Scenario.load(SCENARIO, set=["method.planner.nope=1"])
    with pytest.raises(msbench.ConfigError, match=r"frontend\.mistrack_share"):
        msbench.Scenario.load(SCENARIO, set=["frontend.mistrack_share=0.9"])
    with pytest.raises(msbench.ConfigError, match="file not found"):
        msbench.Scenario.load("/nonexistent/scenario.yaml")
    assert issubclass(msbench.ConfigError, ValueError)


def test_effective_configuration_is_the_full_one(fast_scenario):
    e = fast_scenario.effective()
    assert e["duration_s"] == 6
    assert e["camera_stream"]["renderer"] == "blank"
    assert e["frontend"]["drift_scale"] == 1.0
    assert e["method"]["type"] == "monospheres"
    assert fast_scenario.method == "monospheres" and fast_scenario.seed == 1


def test_frames_are_read_only_views_that_outlive_the_step(fast_scenario):
    m = msbench.Mission(fast_scenario)
    t = m.step(500)
    assert t.frame is not None and t.frame.dtype == np.uint8 and t.frame.ndim == 2
    assert not t.frame.flags.writeable
    with pytest.raises(ValueError):
        t.frame[0, 0] = 1
    assert t.true_pose.shape == (4, 4) and t.est_pose.shape == (4, 4)
    old, copy, old_tick = t.frame, t.frame.copy(), t.frame_tick
    later = m.step(1000)
    assert later.frame_tick > old_tick
    assert np.array_equal(old, copy)  # the loop rendered the next frames elsewhere
    del t, later
    assert old.sum() == copy.sum()    # still valid with only the view left
    points = None
    while m.running and points is None:
        points = m.step(100).points
    assert points is not None and points.shape[1] == 3


def test_same_hash_as_the_command_line_and_the_same_files(tmp_path):
    sets = fast_sets()
    h = run_hash(sets)
    assert run_hash(sets) == h  # twice
    cli = subprocess.run([MSBENCH_BIN, "run", SCENARIO, "--quiet", "--out", str(tmp_path / "cli")] +
                         sum([["--set", s] for s in sets], []), capture_output=True, text=True, check=True)
    assert f"hash {h}" in cli.stdout
    m = msbench.Mission(msbench.Scenario.load(SCENARIO, set=sets))
    m.run(progress=False)
    out = m.write(str(tmp_path / "py"))
    for name in ("coverage.csv", "trajectory.csv"):
        assert (tmp_path / "cli" / name).read_bytes() == (tmp_path / "py" / name).read_bytes()
    assert m.result()["determinism_hash"] == h
    with pytest.raises(msbench.ConfigError, match="--out|not empty|exists"):
        m.write(out)  # never over a result


def _hash_in_child(queue):
    queue.put(run_hash(fast_sets()))


def test_same_hash_in_a_spawned_process_and_beside_a_busy_thread():
    h = run_hash(fast_sets())
    ctx = multiprocessing.get_context("spawn")
    q = ctx.Queue()
    p = ctx.Process(target=_hash_in_child, args=(q,))
    p.start()
    child = q.get(timeout=120)
    p.join()
    assert child == h
    stop = threading.Event()

    def busy():
        x = 0.0
        while not stop.is_set():
            x = (x + 1.2345) % 97.0

    t = threading.Thread(target=busy)
    t.start()
    try:
        assert run_hash(fast_sets()) == h
    finally:
        stop.set()
        t.join()


def test_step_releases_the_gil(fast_scenario):
    # A Python thread keeps counting while C++ steps the loop.
    m = msbench.Mission(fast_scenario)
    count = [0]
    stop = threading.Event()

    def counter():
        while not stop.is_set():
            count[0] += 1

    t = threading.Thread(target=counter)
    t.start()
    before = count[0]
    m.step(2000)
    during = count[0] - before
    stop.set()
    t.join()
    assert during > 1000


def test_ctrl_c_stops_a_run_and_leaves_nothing(tmp_path):
    out = tmp_path / "run"
    script = (f"import msbench\n"
              f"m = msbench.Mission(msbench.Scenario.load({SCENARIO!r}, set={fast_sets(duration_s=600, seed=2)!r}))\n"  # seed 1 collides at 9 s
              f"print('started', flush=True)\n"
              f"m.run(progress=False)\n"
              f"m.write({str(out)!r})\n")
    env = dict(os.environ)
    p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         env=env, cwd=SOURCE_DIR)
    assert p.stdout.readline().strip() == "started"
    time.sleep(1.0)
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=60)
    assert p.returncode != 0
    assert "KeyboardInterrupt" in err
    assert not out.exists() and not (tmp_path / "run.partial").exists()


def test_result_before_the_end_is_refused(fast_scenario):
    m = msbench.Mission(fast_scenario)
    m.step(10)
    with pytest.raises(RuntimeError, match="still running"):
        m.result()
    with pytest.raises(ValueError):
        m.step(0)


def test_write_never_replaces_what_the_mission_reads(tmp_path):
    # Before: write(dir, overwrite=True) into an msbench output holding the scenario (a run's
    # config.yaml, replayed) deleted it.
    import shutil
    m = msbench.Mission(msbench.Scenario.load(SCENARIO, set=fast_sets(duration_s=2)))
    m.run(progress=False)
    first = pathlib.Path(m.write(str(tmp_path / "run")))
    replay = msbench.Mission(str(first / "config.yaml"))
    replay.run(progress=False)
    with pytest.raises(Exception, match="overlaps the input SCENARIO"):
        replay.write(str(first), overwrite=True)
    assert (first / "config.yaml").exists()
    # A base: file inside the output directory is an input too.
    (tmp_path / "top.yaml").write_text(f"base: {first / 'config.yaml'}\n")
    top = msbench.Mission(str(tmp_path / "top.yaml"))
    top.run(progress=False)
    with pytest.raises(Exception, match="base: file"):
        top.write(str(first), overwrite=True)
    assert (first / "config.yaml").exists()
