"""A scenario's Python method in its own, confined process (docs/python.md, "A method in its own
process"): msbench starts `_method_host.py`, which confines itself with Linux Landlock and imports
the method; the mission talks to it through the method's calls only, each within a wall-clock
budget. A method that hangs, deadlocks or exits ends the run with status `method_timeout` or
`method_exited`; Ctrl-C and SIGTERM still end msbench at once."""
import json
import os
import pickle
import select
import shutil
import signal
import site
import struct
import subprocess
import sys
import sysconfig
import tempfile
import time
import weakref

from ._msbench import ConfigError, MethodExited, MethodProtocolError, MethodTimeout, RngStream, worlds_dir

_HOST = os.path.join(os.path.dirname(os.path.abspath(__file__)), "_method_host.py")
_MAX_ANSWER_BYTES = 1 << 29  # 512 MiB: the element limit's worst case is far below
_FILE_LIMIT_BYTES = 64 << 20  # each file the method writes (its output log included)
_LOG_TAIL_LINES = 40

_signal_fd = None  # the read end of the runner's signal wakeup pipe (msbench run), if any
_workers = weakref.WeakSet()


class Interrupted(KeyboardInterrupt):
    """A signal that arrived while msbench waited for the method on the loop's second thread."""

    def __init__(self, signum):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def watch_signals():
    """Lets a wait for the method end at a signal on any thread (the runner's main calls this)."""
    global _signal_fd
    r, w = os.pipe()
    os.set_blocking(w, False)
    signal.set_wakeup_fd(w, warn_on_full_buffer=False)
    _signal_fd = r


def close_all():
    """Ends every method process (the record is written after they are gone)."""
    for w in list(_workers):
        w.close()


def _excluded():
    """What a method may never read: msbench's Python package, its worlds and its binaries."""
    out = [os.path.dirname(os.path.abspath(__file__)), os.path.realpath(worlds_dir)]
    for exe in (shutil.which("msbench"), os.environ.get("MSBENCH_BIN")):
        if exe:
            out.append(os.path.realpath(exe))
    return [os.path.realpath(p) for p in out]


def _allowed_reads(method_dir):
    """(read+execute, read-only) trees: the Python installation, its libraries, /etc, the method."""
    read_exec = ["/usr", "/lib", "/lib64", "/bin", sys.prefix, sys.base_prefix, sys.exec_prefix]
    # The installation's own directories only (not sys.path: it holds the working directory).
    read_only = [sysconfig.get_paths()[k] for k in ("stdlib", "platstdlib", "purelib", "platlib")]
    read_only += site.getsitepackages() + [site.getusersitepackages()]
    read_only += ["/etc", "/sys/devices/system/cpu"] + ([method_dir] if method_dir else [])

    def real(paths):
        return sorted({os.path.realpath(p) for p in paths if os.path.exists(p)})

    return real(read_exec), real(read_only)


class _Worker:
    """One method process and its pipes."""

    def __init__(self, entry, method_dir, params, context, budget_s, scenario_file, memory_limit_mib=4096,
                 kind="method"):
        self.budget_s, self.entry, self.memory_limit_mib = budget_s, entry, memory_limit_mib
        key = "method" if kind == "method" else "goals"  # the scenario's section, in errors
        # A method directory that holds msbench is refused before any process starts.
        excluded = _excluded()
        if method_dir and any(e == method_dir or e.startswith(method_dir.rstrip("/") + "/") for e in excluded):
            raise ConfigError(f"{scenario_file}: key '{key}.path': {method_dir} holds msbench itself (its package, "
                              "worlds or binary), which a method may not read: give the method its own directory")
        read_exec, read_only = _allowed_reads(method_dir)
        self.scratch = tempfile.mkdtemp(prefix="msbench-method-")
        self.log_path = os.path.join(self.scratch, "method.log")
        self.rngs = {}
        self.seed = context["seed"]
        self.failure = None  # the timeout or exit that ended the process, if one did
        self.map_source = None  # a goal chooser's GoalRequest while its call runs (its map answers)
        to_host_r, self.to_host = os.pipe()
        self.from_host, from_host_w = os.pipe()
        # A minimal environment: nothing of msbench's (its paths, tokens, settings) reaches the method.
        env = {"PATH": "/usr/bin:/bin", "LANG": "C.UTF-8", "HOME": self.scratch, "TMPDIR": self.scratch}
        with open(self.log_path, "wb") as log:
            # -I: isolated (no user site and its .pth files, no PYTHON* variables, no script directory
            # on sys.path): nothing runs in the host before it confines itself but the host.
            self.proc = subprocess.Popen([sys.executable, "-I", _HOST, str(to_host_r), str(from_host_w)],
                                         stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
                                         pass_fds=(to_host_r, from_host_w), env=env, cwd=self.scratch,
                                         start_new_session=True)
        os.close(to_host_r)
        os.close(from_host_w)
        _workers.add(self)
        self._finalizer = weakref.finalize(self, _Worker._kill, self.proc, self.scratch,
                                           [self.to_host, self.from_host])
        self._send({"kind": kind, "entry": entry, "path": method_dir, "params": params, "context": context,
                    "read_exec": read_exec, "read_only": read_only, "scratch": self.scratch,
                    "excluded": excluded, "confine": True, "file_limit_bytes": _FILE_LIMIT_BYTES,
                    "memory_limit_bytes": int(memory_limit_mib) << 20})
        first = self._answer("the factory", 4 * budget_s)
        if "config" in first:
            self.close()
            raise ConfigError(f"{scenario_file}: key '{key}.entry': {first['config']}")
        if "params" in first:
            self.close()
            raise ConfigError(f"{scenario_file}: key '{key}.params': {first['params']}")
        if "error" in first:
            self.close()
            raise ConfigError(f"{scenario_file}: the {'method' if kind == 'method' else 'goal chooser'}'s factory "
                              f"raised:\n{first['error']}")
        self.ready = first["ready"]

    # --- the pipes -------------------------------------------------------------------------------

    def _send(self, message):
        data = pickle.dumps(message, protocol=5)
        data = struct.pack("<Q", len(data)) + data
        try:
            while data:
                data = data[os.write(self.to_host, data):]
        except (BrokenPipeError, OSError):
            pass  # the process is gone: the answer's wait says how

    def _read(self, n, deadline, what, budget_s):
        chunks = []
        while n:
            wait = deadline - time.monotonic()
            if wait <= 0:
                raise self._fail(MethodTimeout, f"the method did not answer {what} within {budget_s:g} s "
                                 f"({'4 × ' if budget_s != self.budget_s else ''}method.call_budget_s); its process "
                                 "was stopped")
            fds = [self.from_host] + ([_signal_fd] if _signal_fd is not None else [])
            ready, _, _ = select.select(fds, [], [], min(wait, 1.0))
            if _signal_fd is not None and _signal_fd in ready:
                sig = os.read(_signal_fd, 1)
                if sig and sig[0] in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT):
                    self.close()
                    raise Interrupted(sig[0])
            if self.from_host not in ready:
                continue
            b = os.read(self.from_host, min(n, 1 << 20))
            if not b:
                raise self._fail(MethodExited, f"the method's process ended during {what} ({self._how()})")
            chunks.append(b)
            n -= len(b)
        return b"".join(chunks)

    def _answer(self, what, budget_s=None):
        """The host's next answer, serving the method's random draws meanwhile."""
        budget_s = budget_s or self.budget_s
        deadline = time.monotonic() + budget_s
        while True:
            (n,) = struct.unpack("<Q", self._read(8, deadline, what, budget_s))
            if n > _MAX_ANSWER_BYTES:
                raise self._fail(MethodExited, f"the method answered {what} with {n} bytes (the limit is "
                                 f"{_MAX_ANSWER_BYTES >> 20} MiB); its process was stopped")
            try:
                answer = json.loads(self._read(n, deadline, what, budget_s))
            except (ValueError, RecursionError) as e:  # malformed, or nested beyond Python's stack
                raise self._protocol_error(what, f"an answer that is not JSON msbench reads: {type(e).__name__}")
            if not isinstance(answer, dict):
                raise self._protocol_error(what, "an answer that is not a JSON object")
            if "rng_open" in answer:
                handle, name = self._rng_open(answer["rng_open"], what)
                self.rngs[handle] = RngStream(self.seed, name)
                self._send(True)
            elif "rng" in answer:
                handle, op, args = self._rng_call(answer["rng"], what)
                self._send(getattr(self.rngs[handle], op)(*args))
            elif "map" in answer:
                self._send(self._map_leaves(answer["map"], what))
            else:
                return answer

    # The random-stream requests msbench answers: these operations with these argument types, on
    # a stream the method opened. Anything else stops the method at once, named.
    _RNG_OPS = {"uniform": (), "uniform_range": (float, float), "uniform_int": (int,), "normal": ()}

    def _protocol_error(self, what, message):
        return self._fail(MethodProtocolError, f"the method's process sent a message msbench does not answer during "
                                        f"{what} ({message}); its process was stopped")

    def _rng_open(self, request, what):
        if (not isinstance(request, list) or len(request) != 2 or not isinstance(request[0], int)
                or not isinstance(request[1], str) or len(request[1]) > 200):
            raise self._protocol_error(what, "a malformed random-stream request")
        return request

    def _rng_call(self, request, what):
        if not isinstance(request, list) or len(request) != 3 or not isinstance(request[2], list):
            raise self._protocol_error(what, "a malformed random-stream draw")
        handle, op, args = request
        if handle not in self.rngs:
            raise self._protocol_error(what, f"a draw from stream {handle!r}, which it never opened")
        kinds = self._RNG_OPS.get(op) if isinstance(op, str) else None
        if kinds is None:
            raise self._protocol_error(what, f"the random-stream operation {str(op)[:60]!r}")
        if len(args) != len(kinds) or not all(isinstance(a, k) and not isinstance(a, bool) for a, k in zip(args, kinds)):
            if not (len(args) == len(kinds) and all(isinstance(a, (int, float)) for a in args)):
                raise self._protocol_error(what, f"arguments {str(args)[:60]} for {op}")
        return handle, op, [k(a) for a, k in zip(args, kinds)]

    def _map_leaves(self, which, what):
        """A goal chooser's map request during its call: the OctoMap's free or occupied leaves."""
        if self.map_source is None:
            raise self._protocol_error(what, "a map request outside a goal check on the grid's map")
        if which not in ("free", "occupied"):
            raise self._protocol_error(what, f"the map request {str(which)[:60]!r}")
        return getattr(self.map_source, which)()

    def call(self, op, arg=None):
        if self.failure is not None:
            raise type(self.failure)(str(self.failure))  # the first failure names the run's end
        if self.proc is None:
            raise MethodExited(f"the method's process is gone ({op}() asked after the run ended)")
        self._send((op, arg))
        answer = self._answer(f"{op}()")
        if "memory" in answer:
            raise self._fail(MethodExited, f"the method's process reached its memory limit ({self.memory_limit_mib:g} "
                                           f"MiB, method.memory_limit_mib) during {answer['memory']}; it was stopped")
        if "error" in answer:
            raise RuntimeError("the method raised in its own process:\n" + answer["error"])
        return answer["ok"]

    # --- the end ---------------------------------------------------------------------------------

    def _fail(self, kind, message):
        """Stops the process for good; the failure (with the method's last output) that every
        later call raises again, so the first one names the run's end."""
        self.failure = kind(message + self._log_tail())
        self.close(show_output=False)
        return self.failure

    def _how(self):
        try:
            code = self.proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            return "its pipe closed"
        if code < 0:
            name = signal.Signals(-code).name
            why = ", a file it wrote passed the limit" if -code == signal.SIGXFSZ else ""
            return f"killed by {name}{why}"
        return f"exit code {code}"

    def _log_tail(self):
        try:
            with open(self.log_path, "rb") as f:
                f.seek(0, os.SEEK_END)
                f.seek(max(0, f.tell() - 8192))
                lines = f.read().decode(errors="replace").splitlines()[-_LOG_TAIL_LINES:]
        except OSError:
            return ""
        return ("\nthe method's output (its last lines):\n" + "\n".join(lines)) if lines else ""

    @staticmethod
    def _kill(proc, scratch, fds):
        if proc is not None and proc.poll() is None:
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except OSError:
                pass
            proc.wait()
        for fd in fds:
            try:
                os.close(fd)
            except OSError:
                pass
        shutil.rmtree(scratch, ignore_errors=True)

    def close(self, show_output=True):
        """Stops the process (and what it started), its pipes and its scratch directory; shows
        the last lines the method printed."""
        if self.proc is None:
            return
        tail = self._log_tail() if show_output else ""
        if tail:
            print(tail.lstrip("\n"), file=sys.stderr)
        self._finalizer()
        self.proc = None


class _Proxy:
    """The method as the mission calls it: observe, plan, free_space (and snapshot, counters
    when the method has them), each answered by its process."""

    def __init__(self, worker):
        self._worker = worker
        self.msbench_process_id = worker.proc.pid  # its CPU time is charged (timing.compute: charged)
        self.msbench_confinement = _confinement(worker)
        if worker.ready["snapshot"]:
            self.snapshot = lambda: worker.call("snapshot")
        if worker.ready["counters"]:
            self.counters = lambda: worker.call("counters")

    def observe(self, frame):
        self._worker.call("observe", {k: getattr(frame, k) for k in ("tick", "t_s", "pose", "points", "covariances",
                                                                      "track_ids")})

    def plan(self, vehicle):
        return self._worker.call("plan", {k: getattr(vehicle, k) for k in ("tick", "t_s", "yaw_rad", "path_finished",
                                                                            "pose", "position", "velocity")})

    def free_space(self):
        return self._worker.call("free_space")


def _confinement(worker):
    """How a process was confined, as its record says (an unconfined one is never ranked)."""
    ready = worker.ready
    namespace = ready.get("no_pid_namespace", "")
    return ((f"own process, Landlock ABI {ready['landlock_abi']}" if ready["landlock_abi"]
             else "own process, unconfined (no Landlock)") +
            f", {worker.memory_limit_mib:g} MiB" +
            (f", runs as {ready['user']}" if ready.get("user") else "") +
            (", own PID namespace" if not namespace else f", no PID namespace ({namespace})") +
            (", no sockets, memfd, exec or io_uring, native system calls only" if not ready.get("no_seccomp") else f", sockets allowed ({ready['no_seccomp']})"))


class _ChooserProxy:
    """A scenario's goal chooser as msbench calls it: chooser(request) answered by its process.
    A GoalRequest's map (free(), occupied()) is served on the chooser's demand during the call."""

    def __init__(self, worker):
        self._worker = worker
        self.msbench_process_id = worker.proc.pid
        self.msbench_confinement = "goal chooser: " + _confinement(worker)

    def __call__(self, request):
        if hasattr(request, "needs_goal"):  # the grid's GoalRequest
            payload = {"kind": "grid", "t_s": request.t_s, "needs_goal": request.needs_goal,
                       "position": request.position}
            self._worker.map_source = request
        else:  # MonoSpheres' ViewpointRequest
            payload = {"kind": "viewpoints", **{k: getattr(request, k) for k in ("t_s", "position", "ids", "positions",
                                                                                  "yaws", "path_costs", "values")}}
        try:
            return self._worker.call("goals", payload)
        finally:
            self._worker.map_source = None


def chooser(entry, chooser_dir, params, budget_s, scenario_file, memory_limit_mib=4096):
    """A scenario's goal chooser (its `goals` section) started in its own confined process, as a
    callable proxy: `entry`, or with `params` what `entry(**params)` returns, runs there only."""
    ctx = {"box_min": None, "box_max": None, "start_position": None, "start_yaw_rad": None, "start_pose": None,
           "seed": 0}
    return _ChooserProxy(_Worker(entry, chooser_dir, dict(params or {}), ctx, budget_s, scenario_file,
                                 memory_limit_mib, kind="chooser"))


def factory(entry, method_dir, params, budget_s, scenario_file, memory_limit_mib=4096):
    """A factory(context) that starts the method's process and returns the proxy."""

    def build(context):
        ctx = {k: getattr(context, k) for k in ("box_min", "box_max", "start_position", "start_yaw_rad", "start_pose",
                                                "seed")}
        return _Proxy(_Worker(entry, method_dir, dict(params or {}), ctx, budget_s, scenario_file, memory_limit_mib))

    return build
