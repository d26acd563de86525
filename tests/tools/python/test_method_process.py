"""A scenario's Python method runs in its own confined process (msbench.confined): the same run as
in-process, no read of msbench's truth or package, no write outside its scratch directory, named
statuses for a method that hangs, dies or floods its output, signals that still stop msbench, and
answers of the wrong type named by where they sit."""
import json
import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest

import msbench
from conftest import FAST, MSBENCH_BIN, SOURCE_DIR

sys.path.insert(0, os.path.join(SOURCE_DIR, "examples/python"))
import hover_turn  # noqa: E402

CPP = os.path.join(SOURCE_DIR, "examples/hover_turn.yaml")
PY = os.path.join(SOURCE_DIR, "examples/hover_turn_python.yaml")

# A method that stays on the ground: the body of plan() is the test's.
TEMPLATE = """
import os, sys, time
class M:
    def __init__(self, context, **params):
        self.context, self.params, self.found = context, params, {{}}
{init}
    def observe(self, frame):
        pass
    def plan(self, vehicle):
{plan}
        return None
    def free_space(self):
{free}
        return []
    def counters(self):
        return self.found
"""


def scenario(tmp_path, init="        pass", plan="        pass", free="        pass", budget=None, params=None):
    """A scenario whose Python method is TEMPLATE filled in, in its own directory."""
    d = tmp_path / "method"
    d.mkdir()
    (d / "m.py").write_text(TEMPLATE.format(init=init, plan=plan, free=free))
    text = f"base: {CPP}\nmethod:\n  type: python\n  entry: \"m:M\"\n  path: {d}\n"
    if budget is not None:
        text += f"  call_budget_s: {budget}\n"
    text += f"  params: {json.dumps(params or {})}\n"
    (tmp_path / "s.yaml").write_text(text)
    return str(tmp_path / "s.yaml")


def run(file, out, duration=3, extra=()):
    sets = sum([["--set", s] for s in FAST + [f"duration_s={duration}"] + list(extra)], [])
    return subprocess.run([MSBENCH_BIN, "run", file, "--quiet", "--out", str(out)] + sets, capture_output=True,
                          text=True, timeout=300)


def metrics(out):
    return json.loads((out / "metrics.json").read_text())


def test_the_twin_in_its_own_process_gives_the_cpp_methods_hash_and_says_where_it_ran(tmp_path):
    cpp = msbench.Mission(msbench.Scenario.load(CPP, set=FAST))
    cpp.run(progress=False)
    py = msbench.Mission(msbench.Scenario.load(PY, set=FAST))  # the scenario's method: its own process
    py.run(progress=False)
    assert py.hash == cpp.hash
    conf = py.result()["method_confinement"]
    assert conf.startswith("own process, Landlock ABI"), conf
    assert cpp.result()["method_confinement"] == "compiled into msbench"
    inproc = msbench.Mission(msbench.Scenario.load(CPP, set=FAST), method=hover_turn.factory)
    inproc.run(progress=False)
    assert inproc.hash == cpp.hash and inproc.result()["method_confinement"] == "in-process (unconfined)"


def test_a_confined_method_cannot_read_the_truth_or_msbench_nor_write_outside_its_scratch(tmp_path):
    probes = {
        "worlds": msbench._msbench.worlds_dir,
        "package": os.path.dirname(msbench.__file__),
        "binary": MSBENCH_BIN,
        "scenario": str(tmp_path / "s.yaml"),
    }
    init = textwrap.indent(textwrap.dedent(f"""
        for name, p in {probes!r}.items():
            try:
                os.listdir(p) if os.path.isdir(p) else open(p, 'rb').read(1)
                self.found['read_' + name] = 1
            except PermissionError:
                self.found['read_' + name] = 0
        for name, p in (('out', {str(tmp_path / 'planted')!r}), ('scratch', 'mine.txt')):
            try:
                open(p, 'w').write('x')
                self.found['write_' + name] = 1
            except PermissionError:
                self.found['write_' + name] = 0
        try:
            import msbench
            self.found['import_msbench'] = 1
        except ImportError:
            self.found['import_msbench'] = 0
        try:
            os.kill(os.getppid(), 0)
            self.found['signal_msbench'] = 1
        except PermissionError:
            self.found['signal_msbench'] = 0
    """), " " * 8)
    out = tmp_path / "run"
    r = run(scenario(tmp_path, init=init), out)
    assert r.returncode == 0, r.stderr
    c = metrics(out)["counters"]
    print(c)
    assert c["read_worlds"] == c["read_package"] == c["read_binary"] == c["read_scenario"] == 0
    assert c["write_out"] == 0 and c["write_scratch"] == 1
    assert c["import_msbench"] == 0 and c["signal_msbench"] == 0
    assert not (tmp_path / "planted").exists()


def test_a_method_that_hangs_ends_the_run_as_method_timeout_within_its_budget(tmp_path):
    out = tmp_path / "run"
    t0 = time.monotonic()
    r = run(scenario(tmp_path, plan="        time.sleep(3600)", budget=2), out)
    wall = time.monotonic() - t0
    assert r.returncode == 1, r.stderr
    m = metrics(out)
    assert m["status"] == "method_timeout" and "within 2 s" in m["error"]
    assert wall < 60, wall
    # A sweep's reader takes it as a run that ended in an error, not as a result.
    assert "method_timeout" in r.stderr or "did not answer" in r.stderr


def _processes_with(marker):
    """Pids of the processes whose command line or name holds `marker`."""
    found = []
    for pid in os.listdir("/proc"):
        for what in ("cmdline", "comm"):
            try:
                with open(f"/proc/{pid}/{what}", "rb") as f:
                    if marker.encode() in f.read():
                        found.append(int(pid))
                        break
            except (OSError, ValueError):
                pass
    return found


def test_a_daemon_the_method_starts_does_not_outlive_the_run(tmp_path):
    # A double-forked daemon in a session of its own escaped the method's process group before:
    # it kept running after msbench had exited. Now it lives in the host's PID namespace.
    # (It names itself: no program runs in the confinement, so it cannot exec one.)
    marker = f"msbd{time.monotonic_ns() % 10**11}"
    init = textwrap.indent(textwrap.dedent(f"""
        pid = os.fork()
        if pid == 0:
            os.setsid()
            if os.fork() == 0:
                import ctypes
                ctypes.CDLL(None).prctl(15, b"{marker}", 0, 0, 0)  # PR_SET_NAME
                time.sleep(3600)
            os._exit(0)
        os.waitpid(pid, 0)
        time.sleep(0.5)
    """), " " * 8)
    out = tmp_path / "run"
    r = run(scenario(tmp_path, init=init), out)
    assert r.returncode == 0, r.stderr
    assert "own PID namespace" in metrics(out)["method_confinement"], metrics(out)["method_confinement"]
    deadline = time.monotonic() + 10
    while _processes_with(marker) and time.monotonic() < deadline:
        time.sleep(0.2)
    left = _processes_with(marker)
    for pid in left:
        os.kill(pid, signal.SIGKILL)
    assert not left, f"the daemon outlived the run: {left}"


def test_a_confined_method_opens_no_socket_and_runs_nothing_from_memory(tmp_path):
    # Landlock stops TCP bind and connect; UDP, pathname and netlink sockets and memfd (code run
    # from memory) were open before: seccomp refuses socket() and memfd_create() now, while
    # socketpair() (multiprocessing's pipes) still works.
    init = textwrap.indent(textwrap.dedent("""
        import socket
        def tries(f):
            try:
                f()
                return 1.0
            except PermissionError:
                return 0.0
        self.found['udp'] = tries(lambda: socket.socket(socket.AF_INET, socket.SOCK_DGRAM).close())
        self.found['unix'] = tries(lambda: socket.socket(socket.AF_UNIX, socket.SOCK_STREAM).close())
        self.found['netlink'] = tries(lambda: socket.socket(socket.AF_NETLINK, socket.SOCK_RAW).close())
        self.found['memfd'] = tries(lambda: os.close(os.memfd_create('x')))
        self.found['socketpair'] = tries(lambda: [x.close() for x in socket.socketpair()])
        # io_uring makes sockets and opens files without socket() or open(): io_uring_setup(8, p).
        import ctypes
        libc = ctypes.CDLL(None, use_errno=True)
        params = ctypes.create_string_buffer(120)
        self.found['io_uring'] = 1.0 if libc.syscall(425, 8, params) >= 0 else 0.0
        # A program it wrote, run through the dynamic loader (Landlock's execute right does not
        # see it: the loader is the program), and a program of the installation.
        import shutil
        shutil.copy("/bin/true", "copy")
        self.found['ld.so'] = tries(lambda: os.execv("/lib64/ld-linux-x86-64.so.2", ["ld.so", "./copy"]))
        self.found['exec'] = tries(lambda: os.execv("/bin/true", ["true"]))
    """), " " * 8)
    out = tmp_path / "run"
    r = run(scenario(tmp_path, init=init), out)
    assert r.returncode == 0, r.stderr
    m = metrics(out)
    assert m["counters"] == {"udp": 0.0, "unix": 0.0, "netlink": 0.0, "memfd": 0.0, "socketpair": 1.0, "ld.so": 0.0,
                             "exec": 0.0, "io_uring": 0.0}, m["counters"]
    assert "no sockets, memfd, exec or io_uring, native system calls only" in m["method_confinement"], \
        m["method_confinement"]


I386_SOCKET = r"""
long msb_i386_socket(void) {
  long ret;  /* socket(AF_INET, SOCK_DGRAM, 0) through the i386 ABI: number 359 */
  __asm__ volatile("int $0x80" : "=a"(ret) : "a"(359L), "b"(2L), "c"(2L), "d"(0L) : "memory");
  return ret;
}
"""


@pytest.mark.skipif(os.uname().machine != "x86_64", reason="the i386 ABI exists on x86-64 only")
def test_a_system_call_through_another_abi_ends_the_method(tmp_path):
    # A library the method ships makes its calls through i386's `int 0x80`, which the filter's
    # native numbers do not see: before, it opened a UDP socket (and could connect pathname
    # sockets, exec programs). Now any call from another ABI kills the method's process.
    init = textwrap.indent(textwrap.dedent("""
        import ctypes
        shipped = ctypes.CDLL(os.path.join(os.path.dirname(__file__), "libi386.so"))
        shipped.msb_i386_socket.restype = ctypes.c_long
        self.found['i386_socket'] = 1.0 if shipped.msb_i386_socket() >= 0 else 0.0
    """), " " * 8)
    file = scenario(tmp_path, init=init)
    (tmp_path / "i386.c").write_text(I386_SOCKET)
    subprocess.run(["cc", "-shared", "-fPIC", "-O1", "-o", str(tmp_path / "method" / "libi386.so"),
                    str(tmp_path / "i386.c")], check=True)
    out = tmp_path / "run"
    r = run(file, out)
    m = metrics(out)
    assert m["status"] == "method_exited", (m["status"], m.get("counters"), r.stderr[-2000:])
    assert "SIGSYS" in m.get("error", "") + r.stderr, (m.get("error"), r.stderr[-2000:])


def test_a_confined_method_spawns_within_its_task_limit_and_the_run_goes_on(tmp_path):
    # A fork bomb: before, nothing bounded the processes a method started. Now its own user
    # namespace holds at most 256 tasks (RLIMIT_NPROC); the rest fail, and the run completes.
    init = textwrap.indent(textwrap.dedent("""
        n = 0
        for _ in range(1000):
            try:
                pid = os.fork()
            except BlockingIOError:
                break
            if pid == 0:
                time.sleep(3600)
            n += 1
        self.found['children'] = float(n)
    """), " " * 8)
    out = tmp_path / "run"
    r = run(scenario(tmp_path, init=init), out)
    assert r.returncode == 0, r.stderr
    m = metrics(out)
    assert 100 < m["counters"]["children"] < 256, m["counters"]
    assert m["status"] == "completed"


@pytest.mark.skipif(os.geteuid() != 0, reason="the drop from root happens only when msbench runs as root")
def test_a_method_of_root_runs_as_nobody_and_reads_no_secret(tmp_path):
    # As root, the method read /etc/shadow through Landlock's read-only /etc. Now it runs as
    # nobody (its directory, inside pytest's 0700 temporary directory, still imports).
    init = textwrap.indent(textwrap.dedent("""
        self.found['uid'] = float(os.getuid())
        try:
            open('/etc/shadow').read()
            self.found['shadow'] = 1.0
        except PermissionError:
            self.found['shadow'] = 0.0
    """), " " * 8)
    out = tmp_path / "run"
    r = run(scenario(tmp_path, init=init), out)
    assert r.returncode == 0, r.stderr
    m = metrics(out)
    assert m["counters"] == {"uid": 65534.0, "shadow": 0.0}, m["counters"]
    assert "runs as nobody" in m["method_confinement"], m["method_confinement"]


def test_a_method_past_its_memory_limit_ends_the_run_as_method_exited(tmp_path):
    out = tmp_path / "run"
    file = scenario(tmp_path, plan="        self.hog = bytearray(2 << 30)")
    with open(file, "a") as f:
        f.write("  memory_limit_mib: 512\n")
    r = run(file, out)
    assert r.returncode == 1, r.stderr
    m = metrics(out)
    assert m["status"] == "method_exited", m
    assert "memory limit (512 MiB, method.memory_limit_mib) during plan()" in m["error"], m["error"]


def test_a_factory_that_hangs_writes_the_method_timeout_record(tmp_path):
    # Before: a 20-line traceback and no record at all (a sweep saw a run without metrics.json).
    out = tmp_path / "run"
    r = run(scenario(tmp_path, init="        time.sleep(3600)", budget=1), out)
    assert r.returncode == 1, r.stderr
    assert "Traceback" not in r.stderr and "recorded in" in r.stderr, r.stderr
    m = metrics(out)
    assert m["status"] == "method_timeout" and m["error_tick"] == 0, m
    assert "the factory within 4 s (4 × method.call_budget_s)" in m["error"], m["error"]
    assert (out / "config.yaml").exists() and "record_digest" not in m


def test_a_factory_whose_process_ends_writes_the_method_exited_record(tmp_path):
    out = tmp_path / "run"
    r = run(scenario(tmp_path, init="        os._exit(5)"), out)
    assert r.returncode == 1, r.stderr
    m = metrics(out)
    assert m["status"] == "method_exited" and "exit code 5" in m["error"], m["error"]


@pytest.mark.parametrize("plan, why", [("        os._exit(3)", "exit code 3"),
                                       ("        os.kill(os.getpid(), 9)", "SIGKILL"),
                                       ("        while True: print('x' * 4096)", "SIGXFSZ")])
def test_a_method_whose_process_ends_ends_the_run_as_method_exited(tmp_path, plan, why):
    out = tmp_path / "run"
    r = run(scenario(tmp_path, plan=plan), out)
    assert r.returncode == 1, r.stderr
    m = metrics(out)
    assert m["status"] == "method_exited" and why in m["error"], m["error"]


@pytest.mark.parametrize("threads", [[], ["perception.latency_frames=1", "perception.threads=2"]])
def test_sigterm_stops_msbench_while_its_method_hangs(tmp_path, threads):
    # Also when the method's call comes from the pipelined loop's second thread.
    file = scenario(tmp_path, plan="        time.sleep(3600)", budget=3600)
    sets = sum([["--set", s] for s in FAST + ["duration_s=5"] + threads], [])
    p = subprocess.Popen([MSBENCH_BIN, "run", file, "--quiet", "--out", str(tmp_path / "run")] + sets,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(6)  # the loop is waiting for plan()
    p.send_signal(signal.SIGTERM)
    _, err = p.communicate(timeout=30)
    assert p.returncode == 128 + signal.SIGTERM, err
    assert "interrupted" in err and not (tmp_path / "run").exists()


def test_an_answer_of_the_wrong_type_names_where_it_sits(tmp_path):
    out = tmp_path / "run"
    r = run(scenario(tmp_path, free="        return [(1, 0.0, object(), 1.0, 2.0)]"), out)
    assert r.returncode == 1, r.stderr
    m = metrics(out)
    assert m["status"] == "error" and "free_space()[0][2] is a object" in m["error"], m["error"]


def test_a_confined_methods_random_streams_are_msbenchs(tmp_path):
    init = "        self.found['draw'] = context.rng('goals').uniform_range(0.0, 10.0)"
    out = tmp_path / "run"
    r = run(scenario(tmp_path, init=init), out, extra=["seed=5"])
    assert r.returncode == 0, r.stderr
    assert metrics(out)["counters"]["draw"] == msbench.RngStream(5, "goals").uniform_range(0.0, 10.0)


def test_a_method_path_that_holds_msbench_is_refused(tmp_path):
    (tmp_path / "s.yaml").write_text(f"base: {CPP}\nmethod:\n  type: python\n  entry: \"m:M\"\n  path: {SOURCE_DIR}\n"
                                     "  params: {}\n")
    r = run(str(tmp_path / "s.yaml"), tmp_path / "run")
    assert r.returncode == 2 and "key 'method.path'" in r.stderr and "its own directory" in r.stderr, r.stderr


def test_the_method_process_starts_isolated_with_a_minimal_environment(tmp_path):
    # A .pth file in the user site of the HOME msbench runs with is never run by the method's
    # process (python -I), and msbench's environment does not reach the method.
    home = tmp_path / "home"
    site = subprocess.run([sys.executable, "-c", "import site; print(site.getusersitepackages())"],
                          env={**os.environ, "HOME": str(home)}, capture_output=True, text=True).stdout.strip()
    os.makedirs(site)
    with open(os.path.join(site, "evil.pth"), "w") as f:
        f.write("import builtins; builtins.PWNED = 'yes'\n")
    init = ("        import builtins\n"
            "        self.found['pwned'] = float(hasattr(builtins, 'PWNED'))\n"
            "        self.found['secret'] = float('MSBENCH_TEST_SECRET' in os.environ)")
    out = tmp_path / "run"
    sets = sum([["--set", s] for s in FAST + ["duration_s=2"]], [])
    r = subprocess.run([MSBENCH_BIN, "run", scenario(tmp_path, init=init), "--quiet", "--out", str(out)] + sets,
                       capture_output=True, text=True, timeout=300,
                       env={**os.environ, "HOME": str(home), "MSBENCH_TEST_SECRET": "1"})
    assert r.returncode == 0, r.stderr
    assert metrics(out)["counters"] == {"pwned": 0.0, "secret": 0.0}


@pytest.mark.parametrize("request_, says", [
    ("host.ask_rng(h, '__class__', ())", "operation '__class__'"),
    ("host.ask_rng(99, 'uniform', ())", "stream 99"),
    ("host.ask_rng(h, 'uniform_range', ('a', 'b'))", "arguments"),
])
def test_a_random_stream_request_msbench_does_not_answer_stops_the_method_naming_it(tmp_path, request_, says):
    # The method reaches its host through the stream object it was given (as a cheater would).
    init = ("        r = context.rng('goals')\n"
            "        host, h = r._host, r._handle\n"
            f"        self.found['x'] = float(bool({request_}))")
    out = tmp_path / "run"
    t0 = time.monotonic()
    r = run(scenario(tmp_path, init=init), out)
    assert time.monotonic() - t0 < 60
    assert r.returncode != 0
    assert "does not answer" in r.stderr and says in r.stderr, r.stderr
    # Its own status (before: method_exited, as if the process had died; and no record at all
    # from the factory).
    m = metrics(out)
    assert m["status"] == "method_protocol_error" and says in m["error"], m
