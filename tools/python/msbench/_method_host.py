"""The process a Python method or goal chooser runs in (docs/python.md, "A method in its own process").

msbench starts it as `python3 -I _method_host.py RFD WFD` and never imports it: this file
imports nothing of msbench. It confines itself — Linux Landlock (read-only to the Python
installation, /etc and the method's own directory; writes only in its scratch directory; no
network; no signals or abstract sockets outside), nobody instead of root, a memory limit, its
own user and PID namespaces (at most 256 tasks, none outliving it), seccomp (no socket(),
memfd_create() or execve()) — then imports the method and answers msbench's calls over two
pipes. msbench -> host: pickled (op, argument) messages; host -> msbench: JSON only (msbench
never unpickles what a method wrote). Every message is an 8-byte little-endian length and its
bytes.
"""
import ctypes
import importlib
import json
import os
import pickle
import resource
import signal
import struct
import sys
import traceback
import types

# Landlock's system calls and flags (include/uapi/linux/landlock.h; x86-64 and arm64 numbers).
_SYS_CREATE, _SYS_ADD_RULE, _SYS_RESTRICT = 444, 445, 446
_PR_SET_NO_NEW_PRIVS, _PR_SET_PDEATHSIG = 38, 1
_FS_EXECUTE, _FS_WRITE_FILE, _FS_READ_FILE, _FS_READ_DIR = 1 << 0, 1 << 1, 1 << 2, 1 << 3
_FS_TRUNCATE, _FS_IOCTL_DEV = 1 << 14, 1 << 15
_NET_ALL = (1 << 0) | (1 << 1)                  # bind and connect TCP (ABI 4)
_SCOPE_ALL = (1 << 0) | (1 << 1)                # abstract unix sockets and signals (ABI 6)
_FILE_RIGHTS = _FS_EXECUTE | _FS_WRITE_FILE | _FS_READ_FILE | _FS_TRUNCATE | _FS_IOCTL_DEV
_CLONE_NEWUSER, _CLONE_NEWPID = 0x10000000, 0x20000000


def _pid_namespace_init(host_alive):
    """The PID namespace's init (the host's first child): reaps what is orphaned in it and ends
    with the host (SIGKILL at its death, or `host_alive` read to its end); the kernel then kills
    every process left in the namespace."""
    os.closerange(3, host_alive)  # not the host's pipes: msbench must see them close with the host
    os.closerange(host_alive + 1, 1 << 16)
    import select
    while True:
        try:
            while os.waitpid(-1, os.WNOHANG)[0] > 0:
                pass
        except ChildProcessError:
            pass
        if select.select([host_alive], [], [], 1.0)[0]:
            os._exit(0)


def own_pid_namespace(libc):
    """Puts every process the method starts into a PID namespace of its own whose init dies with
    the host, so that nothing the method started (a double-forked daemon included) outlives the
    run. Unprivileged (drop_root has run: the host is never root here): in a user namespace
    mapping the user to itself. Returns "" or why not."""
    uid, gid = os.geteuid(), os.getegid()
    if libc.unshare(_CLONE_NEWUSER) != 0:
        return f"unshare(CLONE_NEWUSER): {os.strerror(ctypes.get_errno())}"
    for name, text in (("setgroups", "deny"), ("uid_map", f"{uid} {uid} 1"), ("gid_map", f"{gid} {gid} 1")):
        with open(f"/proc/self/{name}", "w") as f:
            f.write(text)
    if libc.unshare(_CLONE_NEWPID) != 0:
        return f"unshare(CLONE_NEWPID): {os.strerror(ctypes.get_errno())}"
    host_alive, keep = os.pipe()  # `keep` stays open in the host while it lives
    if os.fork() == 0:
        libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
        os.close(keep)
        _pid_namespace_init(host_alive)
    os.close(host_alive)
    return ""


def _fs_rights(abi):
    """Every file-system right the kernel's Landlock ABI knows."""
    rights = (1 << 13) - 1            # ABI 1: execute .. make_sym
    if abi >= 2:
        rights |= 1 << 13             # refer
    if abi >= 3:
        rights |= _FS_TRUNCATE
    if abi >= 5:
        rights |= _FS_IOCTL_DEV
    return rights


class _PathBeneath(ctypes.Structure):
    _pack_ = 1
    _fields_ = [("allowed_access", ctypes.c_uint64), ("parent_fd", ctypes.c_int32)]


def _inside(path, root):
    return path == root or path.startswith(root.rstrip("/") + "/")


def _allow(libc, ruleset, path, rights, excluded):
    """Allows `rights` beneath `path`, except beneath any `excluded` path: a directory holding an
    excluded path is opened up child by child (Landlock only allows)."""
    if any(_inside(path, e) for e in excluded):
        return
    if any(_inside(e, path) for e in excluded) and os.path.isdir(path):
        for name in sorted(os.listdir(path)):
            _allow(libc, ruleset, os.path.join(path, name), rights, excluded)
        return
    try:
        fd = os.open(path, os.O_PATH | os.O_CLOEXEC)
    except OSError:
        return  # a dangling link or a path that went away: nothing to allow
    try:
        if not os.path.isdir(path):
            rights &= _FILE_RIGHTS
        rule = _PathBeneath(rights, fd)
        if libc.syscall(_SYS_ADD_RULE, ruleset, 1, ctypes.byref(rule), 0) != 0:
            raise OSError(ctypes.get_errno(), f"landlock_add_rule({path})")
    finally:
        os.close(fd)


# seccomp (include/uapi/linux/seccomp.h, filter.h, audit.h): what Landlock does not cover.
_PR_SET_SECCOMP, _SECCOMP_MODE_FILTER = 22, 2
_SECCOMP_RET_ALLOW, _SECCOMP_RET_ERRNO, _SECCOMP_RET_KILL_PROCESS = 0x7FFF0000, 0x00050000, 0x80000000
_BPF_LD_W_ABS, _BPF_JEQ_K, _BPF_JGE_K, _BPF_RET_K = 0x20, 0x15, 0x35, 0x06
# Per architecture: its audit number and the calls denied (socket, memfd_create, execve, execveat,
# io_uring_setup, io_uring_enter, io_uring_register: io_uring makes sockets without socket()).
_DENIED_CALLS = {0xC000003E: (41, 319, 59, 322, 425, 426, 427),   # x86-64
                 0xC00000B7: (198, 279, 221, 281, 425, 426, 427)}  # arm64


class _SockFilter(ctypes.Structure):
    _fields_ = [("code", ctypes.c_uint16), ("jt", ctypes.c_uint8), ("jf", ctypes.c_uint8), ("k", ctypes.c_uint32)]


class _SockFprog(ctypes.Structure):
    _fields_ = [("len", ctypes.c_uint16), ("filter", ctypes.POINTER(_SockFilter))]


def deny_calls(libc):
    """A seccomp filter: socket() (UDP, pathname and every other socket; socketpair() stays, for
    multiprocessing), memfd_create() (code run from memory), execve() and execveat() (no program
    runs: not one the method wrote, through `ld.so ./copy` or from memory) and io_uring (sockets
    and files without the calls above) fail with EPERM; a call through another ABI — i386's
    `int 0x80`, x32 (bit 30 of the number) — kills the process (the checks above see the native
    numbers only). Needs no_new_privs (set with the Landlock rules). Returns "" or why not."""
    prog = [_SockFilter(_BPF_LD_W_ABS, 0, 0, 4)]  # the architecture
    for arch, numbers in _DENIED_CALLS.items():
        # A block of n + 7: arch?, load nr, x32?, n denied numbers, allow, deny, kill, reload arch.
        n = len(numbers)
        prog += [_SockFilter(_BPF_JEQ_K, 0, n + 5, arch),  # not this one: to the next block
                 _SockFilter(_BPF_LD_W_ABS, 0, 0, 0),  # the call's number
                 _SockFilter(_BPF_JGE_K, n + 2, 0, 0x40000000)]  # an x32 call: kill
        prog += [_SockFilter(_BPF_JEQ_K, n - i, 0, nr) for i, nr in enumerate(numbers)]
        prog += [_SockFilter(_BPF_RET_K, 0, 0, _SECCOMP_RET_ALLOW),
                 _SockFilter(_BPF_RET_K, 0, 0, _SECCOMP_RET_ERRNO | 1),  # EPERM
                 _SockFilter(_BPF_RET_K, 0, 0, _SECCOMP_RET_KILL_PROCESS)]
        prog += [_SockFilter(_BPF_LD_W_ABS, 0, 0, 4)]  # reload the architecture for the next
    prog[-1] = _SockFilter(_BPF_RET_K, 0, 0, _SECCOMP_RET_KILL_PROCESS)  # another ABI (i386): kill
    array = (_SockFilter * len(prog))(*prog)
    fprog = _SockFprog(len(prog), array)
    if libc.prctl(_PR_SET_SECCOMP, _SECCOMP_MODE_FILTER, ctypes.byref(fprog), 0, 0) != 0:
        return f"seccomp: {os.strerror(ctypes.get_errno())}"
    return ""


def landlock_ruleset(libc, read_exec, read_only, scratch, excluded):
    """The Landlock rules (read-only to the installation, /etc and the method's directory; writes
    in its scratch directory only), built while every path can still be opened; (ABI, ruleset fd),
    or (0, None) when the kernel has no Landlock (the run is then recorded as unconfined). Sets
    no_new_privs, which restricting needs."""
    libc.prctl(_PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0)
    abi = libc.syscall(_SYS_CREATE, None, 0, 1)
    if abi <= 0:
        return 0, None
    fs = _fs_rights(abi)
    fields = [fs] + ([_NET_ALL] if abi >= 4 else []) + ([_SCOPE_ALL] if abi >= 6 else [])
    attr = struct.pack(f"<{len(fields)}Q", *fields)
    ruleset = libc.syscall(_SYS_CREATE, ctypes.c_char_p(attr), len(attr), 0)
    if ruleset < 0:
        raise OSError(ctypes.get_errno(), "landlock_create_ruleset")
    read = _FS_READ_FILE | _FS_READ_DIR
    for p in read_exec:
        _allow(libc, ruleset, p, read | _FS_EXECUTE, excluded)
    for p in read_only:
        _allow(libc, ruleset, p, read, excluded)
    _allow(libc, ruleset, scratch, fs & ~_FS_EXECUTE, excluded)  # nothing it writes runs
    _allow(libc, ruleset, "/dev/null", _FS_READ_FILE | _FS_WRITE_FILE, excluded)
    return abi, ruleset


def landlock_restrict(libc, ruleset):
    """Applies the rules to this process and every process it starts, for good."""
    if ruleset is None:
        return
    if libc.syscall(_SYS_RESTRICT, ruleset, 0) != 0:
        raise OSError(ctypes.get_errno(), "landlock_restrict_self")
    os.close(ruleset)


_TASK_LIMIT = 256  # processes and threads of a method's own user namespace (RLIMIT_NPROC)
_NOBODY = 65534  # the unprivileged user a method runs as when msbench runs as root
_PR_SET_DUMPABLE = 4


def drop_root(libc, scratch, method_dir):
    """As root: hands the scratch directory to nobody and becomes nobody (no capabilities, no
    supplementary groups), so that neither root-owned files (/etc/shadow) nor root's powers reach
    the method. The method's directory stays reachable through a descriptor opened before (its
    parents may be closed to others, as /root or pytest's temporary directories are). Returns
    (user, the method directory's path to import from)."""
    if os.geteuid() != 0:
        return "", method_dir
    fd = os.open(method_dir, os.O_PATH | os.O_DIRECTORY) if method_dir else None
    for root, dirs, files in os.walk(scratch):
        for name in dirs + files:
            os.lchown(os.path.join(root, name), _NOBODY, _NOBODY)
    os.chown(scratch, _NOBODY, _NOBODY)
    os.setgroups([])
    os.setresgid(_NOBODY, _NOBODY, _NOBODY)
    os.setresuid(_NOBODY, _NOBODY, _NOBODY)
    libc.prctl(_PR_SET_DUMPABLE, 1, 0, 0, 0)  # its own /proc files (uid_map) stay its own
    libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)  # cleared by the change of user
    if fd is not None and not os.access(method_dir, os.R_OK | os.X_OK):
        method_dir = f"/proc/self/fd/{fd}"
    return "nobody", method_dir


# --- the pipes ---------------------------------------------------------------------------------

def _read_exact(fd, n):
    chunks = []
    while n:
        b = os.read(fd, min(n, 1 << 20))
        if not b:
            raise EOFError
        chunks.append(b)
        n -= len(b)
    return b"".join(chunks)


def _recv(fd):
    (n,) = struct.unpack("<Q", _read_exact(fd, 8))
    return pickle.loads(_read_exact(fd, n))


def _send(fd, obj):
    data = json.dumps(obj).encode()
    data = struct.pack("<Q", len(data)) + data
    while data:
        data = data[os.write(fd, data):]


def _plain(x, where):
    """`x` as JSON data (numbers, strings, lists, dicts, None), or TypeError naming where in the
    answer a value of another type sits."""
    if x is None or isinstance(x, (bool, int, float, str)):
        return x
    if type(x).__module__ == "numpy":
        if hasattr(x, "shape") and x.shape != ():
            return _plain(x.tolist(), where)
        return x.item()
    if isinstance(x, (list, tuple)):
        return [_plain(e, f"{where}[{i}]") for i, e in enumerate(x)]
    if isinstance(x, dict):
        for k in x:
            if not isinstance(k, str):
                raise TypeError(f"{where} has the key {k!r}, not a string")
        return {k: _plain(v, f"{where}[{k!r}]") for k, v in x.items()}
    if hasattr(x, "__iter__") and not isinstance(x, (bytes, bytearray)):
        return _plain(list(x), where)
    raise TypeError(f"{where} is a {type(x).__name__}, not a number, string, sequence or dict")


class _Rng:
    """A method's named random stream: drawn by msbench (the same stream as in-process)."""

    def __init__(self, host, handle):
        self._host, self._handle = host, handle

    def _draw(self, op, *args):
        return self._host.ask_rng(self._handle, op, args)

    def uniform(self):
        return self._draw("uniform")

    def uniform_range(self, lo, hi):
        return self._draw("uniform_range", float(lo), float(hi))

    def uniform_int(self, n):
        return self._draw("uniform_int", int(n))

    def normal(self):
        return self._draw("normal")


class _Host:
    def __init__(self, rfd, wfd):
        self.rfd, self.wfd = rfd, wfd
        self.handles = 0

    def ask_rng(self, handle, op, args):
        _send(self.wfd, {"rng": [handle, op, list(args)]})
        return _recv(self.rfd)

    def context(self, c):
        """The factory's Context, as msbench's: attributes and rng(name)."""
        host = self
        ctx = types.SimpleNamespace(**c)

        def rng(name):
            host.handles += 1
            _send(host.wfd, {"rng_open": [host.handles, str(name)]})
            _recv(host.rfd)
            return _Rng(host, host.handles)

        ctx.rng = rng
        return ctx


def _view(d):
    """A SlamFrame or Vehicle as the method sees it in-process: read-only arrays, plain values."""
    for v in d.values():
        if hasattr(v, "flags"):
            v.flags.writeable = False
    return types.SimpleNamespace(**d)


def _method_calls(method):
    return {
        "observe": lambda a: method.observe(_view(a)),
        "plan": lambda a: method.plan(_view(a)),
        "free_space": lambda a: method.free_space(),
        "snapshot": lambda a: method.snapshot(),
        "counters": lambda a: method.counters(),
    }


class _MapRequest(types.SimpleNamespace):  # noqa: D101
    """The grid's GoalRequest in the chooser's process: free() and occupied() ask msbench for the
    OctoMap's leaves (N×4, read-only), during the call only."""

    def __init__(self, host, fields):
        super().__init__(**fields)
        self._host, self._open = host, True

    def _leaves(self, which):
        if not self._open:
            raise RuntimeError("a GoalRequest's map is valid only during the goals() call")
        _send(self._host.wfd, {"map": which})
        leaves = _recv(self._host.rfd)
        leaves.flags.writeable = False
        return leaves

    def free(self):
        return self._leaves("free")

    def occupied(self):
        return self._leaves("occupied")


def _request(host, a):
    """A goal check's request as the chooser sees it in-process (read-only arrays)."""
    kind = a.pop("kind")
    if kind == "grid":
        return _MapRequest(host, dict(_view(a).__dict__))
    return _view(a)


def _choose(chooser, host, a):
    """One goal check: the chooser's answer; the request's map closes when the call returns."""
    request = _request(host, a)
    try:
        return chooser(request)
    finally:
        request._open = False


def _preload():
    """numpy (the arrays of every frame and request) is imported before the host gives up root:
    it may sit where nobody cannot read (a virtual environment under /root)."""
    try:
        import numpy  # noqa: F401
    except ImportError:
        pass


def _make(init, host, user=""):
    """The method (its factory called with the Context and params) or the goal chooser (entry, or
    entry(**params)); None when it cannot be made (msbench was told why)."""
    wfd = host.wfd
    module_name, _, attr = init["entry"].partition(":")
    try:
        found = getattr(importlib.import_module(module_name), attr, None)
    except BaseException as e:  # noqa: B902
        hint = (" (methods run as nobody when msbench runs as root: the directory and its files must be readable "
                "by others)" if user and isinstance(e, (ImportError, PermissionError)) else "")
        _send(wfd, {"config": f"cannot import '{module_name}': {type(e).__name__}: {e}{hint}"})
        return None
    if not callable(found):
        _send(wfd, {"config": f"'{module_name}' has no callable '{attr}'"})
        return None
    chooser = init["kind"] == "chooser"
    if chooser and not init["params"]:
        return found
    try:
        made = found(**init["params"]) if chooser else found(host.context(init["context"]), **init["params"])
    except TypeError as e:
        _send(wfd, {"params": str(e), "error": "".join(traceback.format_exception(e))})
        return None
    except BaseException as e:  # noqa: B902
        _send(wfd, {"error": "".join(traceback.format_exception(e))})
        return None
    if chooser and not callable(made):
        _send(wfd, {"config": f"'{init['entry']}(**params)' did not return a callable chooser"})
        return None
    return made


def _serve(host, calls):
    while True:
        op, arg = _recv(host.rfd)
        try:
            answer = _plain(calls[op](arg), f"{op}()")
        except MemoryError:  # its memory limit (RLIMIT_AS): the process's end, not the method's error
            _send(host.wfd, {"memory": f"{op}()"})
            os._exit(1)
        except BaseException as e:  # noqa: B902 — SystemExit and KeyboardInterrupt are method errors here
            _send(host.wfd, {"error": "".join(traceback.format_exception(e))})
            continue
        _send(host.wfd, {"ok": answer})


def main():
    rfd, wfd = int(sys.argv[1]), int(sys.argv[2])
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is msbench's: it ends the run
    signal.signal(signal.SIGXFSZ, signal.SIG_DFL)  # a file past its limit ends the process
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    host = _Host(rfd, wfd)
    init = _recv(rfd)
    limit = init["file_limit_bytes"]
    resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    memory = init["memory_limit_bytes"]
    resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
    user, no_namespace, no_seccomp, abi = "", "not confined", "not confined", 0
    if init["confine"]:
        _preload()
        abi, ruleset = landlock_ruleset(libc, init["read_exec"], init["read_only"], init["scratch"], init["excluded"])
        user, init["path"] = drop_root(libc, init["scratch"], init["path"])
        no_namespace = own_pid_namespace(libc)
        if not no_namespace:  # its own user namespace: the count is of its own processes only
            resource.setrlimit(resource.RLIMIT_NPROC, (_TASK_LIMIT, _TASK_LIMIT))
        landlock_restrict(libc, ruleset)
        no_seccomp = deny_calls(libc)
    os.chdir(init["scratch"])
    # The method: its directory first on sys.path, nothing of msbench's.
    sys.path[:] = [p for p in sys.path if not any(_inside(os.path.abspath(p or "."), e) for e in init["excluded"])]
    if init["path"]:
        sys.path.insert(0, init["path"])
    made = _make(init, host, user)
    if made is None:
        return
    ready = {"landlock_abi": abi, "no_pid_namespace": no_namespace, "no_seccomp": no_seccomp, "user": user,
             "task_limit": 0 if no_namespace else _TASK_LIMIT}
    if init["kind"] == "chooser":
        calls = {"goals": lambda a: _choose(made, host, a)}
    else:
        ready.update(snapshot=hasattr(made, "snapshot"), counters=hasattr(made, "counters"))
        calls = _method_calls(made)
    _send(wfd, {"ready": ready})
    try:
        _serve(host, calls)
    except EOFError:
        pass  # msbench closed the pipe: the run is over


if __name__ == "__main__":
    main()
