"""The process a Python method runs in (docs/python.md, "A method in its own process").

msbench starts it as `python3 -E -P _method_host.py RFD WFD` and never imports it: this file
imports nothing of msbench. It confines itself (Linux Landlock: read-only to the Python
installation, /etc and the method's own directory; writes only in its scratch directory; no
network; no signals or abstract sockets outside; a memory limit; every process it starts in a
PID namespace that dies with it), then imports the method and answers msbench's
calls over two pipes. msbench -> host: pickled (op, argument) messages; host -> msbench: JSON
only (msbench never unpickles what a method wrote). Every message is an 8-byte little-endian
length and its bytes.
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
    run. Unprivileged: in a user namespace mapping the user to itself. Returns "" or why not."""
    if os.geteuid() != 0:
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
_SECCOMP_RET_ALLOW, _SECCOMP_RET_ERRNO = 0x7FFF0000, 0x00050000
_BPF_LD_W_ABS, _BPF_JEQ_K, _BPF_JGE_K, _BPF_RET_K = 0x20, 0x15, 0x35, 0x06
# Per architecture: its audit number and the calls denied (socket, memfd_create).
_DENIED_CALLS = {0xC000003E: (41, 319),   # x86-64
                 0xC00000B7: (198, 279)}  # arm64


class _SockFilter(ctypes.Structure):
    _fields_ = [("code", ctypes.c_uint16), ("jt", ctypes.c_uint8), ("jf", ctypes.c_uint8), ("k", ctypes.c_uint32)]


class _SockFprog(ctypes.Structure):
    _fields_ = [("len", ctypes.c_uint16), ("filter", ctypes.POINTER(_SockFilter))]


def deny_sockets_and_memfd(libc):
    """A seccomp filter: socket() (UDP, pathname and every other socket; socketpair() stays, for
    multiprocessing) and memfd_create() (code run from memory) fail with EPERM. Needs
    no_new_privs (set by confine()). Returns "" or why not."""
    prog = [_SockFilter(_BPF_LD_W_ABS, 0, 0, 4)]  # the architecture
    for arch, (socket_nr, memfd_nr) in _DENIED_CALLS.items():
        prog += [_SockFilter(_BPF_JEQ_K, 0, 6, arch),  # not this one: skip its six
                 _SockFilter(_BPF_LD_W_ABS, 0, 0, 0),  # the call's number
                 _SockFilter(_BPF_JGE_K, 3, 0, 0x40000000),  # x32 calls (bit 30): none is needed
                 _SockFilter(_BPF_JEQ_K, 2, 0, socket_nr),
                 _SockFilter(_BPF_JEQ_K, 1, 0, memfd_nr),
                 _SockFilter(_BPF_RET_K, 0, 0, _SECCOMP_RET_ALLOW),
                 _SockFilter(_BPF_RET_K, 0, 0, _SECCOMP_RET_ERRNO | 1)]  # EPERM
        prog += [_SockFilter(_BPF_LD_W_ABS, 0, 0, 4)]  # reload the architecture for the next
    prog[-1] = _SockFilter(_BPF_RET_K, 0, 0, _SECCOMP_RET_ALLOW)  # another architecture: as it is
    array = (_SockFilter * len(prog))(*prog)
    fprog = _SockFprog(len(prog), array)
    if libc.prctl(_PR_SET_SECCOMP, _SECCOMP_MODE_FILTER, ctypes.byref(fprog), 0, 0) != 0:
        return f"seccomp: {os.strerror(ctypes.get_errno())}"
    return ""


def confine(read_exec, read_only, scratch, excluded):
    """Restricts this process for good; returns the Landlock ABI used, or 0 when the kernel has
    none (the run is then recorded as unconfined)."""
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(_PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0)
    abi = libc.syscall(_SYS_CREATE, None, 0, 1)
    if abi <= 0:
        return 0
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
    if libc.syscall(_SYS_RESTRICT, ruleset, 0) != 0:
        raise OSError(ctypes.get_errno(), "landlock_restrict_self")
    os.close(ruleset)
    return abi


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


def _serve(host, method):
    calls = {
        "observe": lambda a: method.observe(_view(a)),
        "plan": lambda a: method.plan(_view(a)),
        "free_space": lambda a: method.free_space(),
        "snapshot": lambda a: method.snapshot(),
        "counters": lambda a: method.counters(),
    }
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
    no_namespace = own_pid_namespace(libc) if init["confine"] else "not confined"
    os.chdir(init["scratch"])
    abi = confine(init["read_exec"], init["read_only"], init["scratch"], init["excluded"]) if init["confine"] else 0
    no_seccomp = deny_sockets_and_memfd(libc) if init["confine"] else "not confined"
    # The method: its directory first on sys.path, nothing of msbench's.
    sys.path[:] = [p for p in sys.path if not any(_inside(os.path.abspath(p or "."), e) for e in init["excluded"])]
    if init["path"]:
        sys.path.insert(0, init["path"])
    module_name, _, attr = init["entry"].partition(":")
    try:
        factory = getattr(importlib.import_module(module_name), attr, None)
    except BaseException as e:  # noqa: B902
        _send(wfd, {"config": f"cannot import '{module_name}': {type(e).__name__}: {e}"})
        return
    if not callable(factory):
        _send(wfd, {"config": f"'{module_name}' has no callable '{attr}'"})
        return
    try:
        method = factory(host.context(init["context"]), **init["params"])
    except TypeError as e:
        _send(wfd, {"params": str(e), "error": "".join(traceback.format_exception(e))})
        return
    except BaseException as e:  # noqa: B902
        _send(wfd, {"error": "".join(traceback.format_exception(e))})
        return
    _send(wfd, {"ready": {"snapshot": hasattr(method, "snapshot"), "counters": hasattr(method, "counters"),
                          "landlock_abi": abi, "no_pid_namespace": no_namespace, "no_seccomp": no_seccomp}})
    try:
        _serve(host, method)
    except EOFError:
        pass  # msbench closed the pipe: the run is over


if __name__ == "__main__":
    main()
