"""`python3 -m msbench run SCENARIO --out DIR [...]`: `msbench run` for scenarios whose method is
written in Python (msbench run hands them here): the same options, files, summary line and exit
codes (0 ok, 1 the run ended in an error, 2 bad input, 130 interrupted)."""
import argparse
import signal
import sys

from . import ConfigError, MethodError, MethodExited, MethodProtocolError, MethodTimeout, Mission, Scenario, confined
from ._msbench import write_start_failure


class _Signalled(KeyboardInterrupt):
    """SIGTERM, SIGHUP or SIGQUIT, raised where Python runs next (a method's call included) so that
    it ends the run as Ctrl-C does: interrupted, nothing written, exit 128 + signal."""

    def __init__(self, signum):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def _raise_signalled(signum, _frame):
    raise _Signalled(signum)


def run(argv):
    p = argparse.ArgumentParser(prog="msbench run")
    p.add_argument("scenario")
    p.add_argument("--out", required=True)
    p.add_argument("--set", action="append", default=[])
    p.add_argument("--seed")
    p.add_argument("--duration")
    p.add_argument("--record")
    p.add_argument("--video", action="store_true")
    p.add_argument("--quiet", action="store_true")
    p.add_argument("--overwrite", action="store_true")
    a = p.parse_args(argv)
    sets = list(a.set)
    if a.seed is not None:
        sets.append(f"seed={a.seed}")
    if a.duration is not None:
        sets.append(f"duration_s={a.duration}")
    if a.video:
        sets.append("video.enabled=true")
    try:
        if a.record:
            raise ConfigError("--record: not available for Python methods (the perception log is the C++ runner's)")
        scenario = Scenario.load(a.scenario, set=sets)
        mission = Mission(scenario)
    except ConfigError as e:
        print(f"msbench run: {e}", file=sys.stderr)
        return 2
    except MethodError as e:  # the method's factory timed out, or its process ended, before the first step
        confined.close_all()
        status = ("method_timeout" if isinstance(e, MethodTimeout) else
                  "method_exited" if isinstance(e, MethodExited) else
                  "method_protocol_error" if isinstance(e, MethodProtocolError) else "error")
        out = write_start_failure(scenario, a.out, status, str(e), overwrite=a.overwrite)
        print(f"msbench run: error: {e} (recorded in {out})", file=sys.stderr)
        return 1
    try:
        mission.run(progress=not a.quiet)
        mission.result()  # the method's last answers (its final map) before its process goes
    except MethodError as e:
        out = mission.write(a.out, overwrite=a.overwrite)
        confined.close_all()
        print(f"msbench run: error: {e} (recorded in {out})", file=sys.stderr)
        return 1
    except KeyboardInterrupt as e:
        confined.close_all()
        print("msbench run: interrupted; nothing written", file=sys.stderr)
        return 128 + getattr(e, "signum", signal.SIGINT)
    confined.close_all()  # the record is written after the method's process is gone
    out = mission.write(a.out, overwrite=a.overwrite)
    print(summary_line(mission.result(), out))
    return 0


def method_label(r):
    """The method as msbench run's summary names it (methodLabel in tools/engine/methods.h): its type,
    each ablation switch that is off, the published code's defects that are on."""
    label = r.get("method", "?") + "".join(f" -{k}" for k, v in sorted(r.get("switches", {}).items()) if v is False)
    on = [k for k, v in sorted(r.get("reference_code", {}).items()) if v is True]
    if on and len(on) == len(r.get("reference_code", {})):
        return label + " +published"
    return label + "".join(f" +{k}" for k in on)


def summary_line(r, out):
    """The result line `msbench run` prints, from a run's metrics (and its collision line)."""
    cov = r["coverage"]
    share = "" if cov.get("box_share") is None else f", {int(100 * cov['box_share'])} % of explorable"
    line = (f"run {r['name']} ({method_label(r)}): {r['status']} after {r['sim_time_s']:.0f} s simulated "
            f"({r['wall_time_s']:.0f} s wall, RTF {r['real_time_factor']:.2f}); A = {cov['area_m2']:.0f} m² "
            f"(box {cov['area_box_m2']:.0f} m²{share}), {r['distance_flown_m']:.0f} m flown; "
            f"hash {r['determinism_hash']} -> {out}")
    c = r.get("collision")
    if c:
        v = c.get("vehicle_position_m", [0, 0, 0])
        line += (f"\nrun {r['name']}: collision at t = {c['t_s']:.1f} s, vehicle at ({v[0]:.1f}, {v[1]:.1f}, "
                 f"{v[2]:.1f}), {c.get('vehicle_geom', '?')} hit {c.get('world_geom', '?')}")
    return line


def main():
    if len(sys.argv) < 2 or sys.argv[1] != "run":
        print("usage: python3 -m msbench run SCENARIO --out DIR [--set KEY=VALUE]... [--seed S] [--duration D] "
              "[--quiet] [--overwrite]", file=sys.stderr)
        return 2
    for sig in (signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT):
        signal.signal(sig, _raise_signalled)
    confined.watch_signals()  # a wait for the method ends at a signal on any thread
    try:
        return run(sys.argv[2:])
    except KeyboardInterrupt as e:  # before the run started (set-up)
        print("msbench run: interrupted; nothing written", file=sys.stderr)
        return 128 + getattr(e, "signum", signal.SIGINT)


if __name__ == "__main__":
    sys.exit(main())
