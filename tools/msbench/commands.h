// The msbench sub-commands. Each parses its own arguments and returns an exit code
// (0 ok, 1 runtime failure, 2 usage or configuration error).
#pragma once

namespace msb {

/// `msbench run SCENARIO.yaml --out DIR`: one closed-loop exploration mission.
int runRunCommand(int argc, char** argv);
/// `msbench export RUN --out DIR`: a run's trajectories (TUM) and map (.bt) for the field's tools.
int runExportCommand(int argc, char** argv);
/// `msbench methods [--type T] [--keys]`: the registered methods and their keys.
int runMethodsCommand(int argc, char** argv);
/// msbench keys: every configuration key with its default and accepted values (docs/keys.md).
int runKeysCommand(int argc, char** argv);
/// `msbench video RUN`: the video of a finished run, from a replay of its config.yaml.
int runVideoCommand(int argc, char** argv);
/// `msbench sweep SWEEP.yaml --out DIR [--jobs N]`: many runs in parallel processes, resumable.
int runSweepCommand(int argc, char** argv);
/// `msbench report DIR [--out R]`: Table I layout, CSV and figures of a sweep directory.
int runReportCommand(int argc, char** argv);
/// `msbench regress DIR --against GOLDEN [--update]`: coverage regression against stored results.
int runRegressCommand(int argc, char** argv);
/// `msbench fly FILE.yaml --out DIR`: a scripted waypoint flight with outputs.
int runFlyCommand(int argc, char** argv);
/// `msbench render-probe --world W --pose x,y,z,yaw --out F.png`: one fisheye frame.
int runRenderProbeCommand(int argc, char** argv);
/// `msbench vio-eval FILE.yaml --out DIR`: perception evaluated against ground truth.
int runVioEvalCommand(int argc, char** argv);
/// `msbench map-replay LOG --out DIR`: the mapper over a recorded perception log.
int runMapReplayCommand(int argc, char** argv);
/// `msbench grid-audit LOG RUN`: how a grid-baseline run's map came to be free where it collided.
int runGridAuditCommand(int argc, char** argv);
/// `msbench bench-map LOG`: the mapper's per-update time.
int runBenchMapCommand(int argc, char** argv);
/// `msbench world list|build|show`: the benchmark worlds.
int runWorldCommand(int argc, char** argv);
/// `msbench bench-loop [--world W]`: closed-loop cost per stage of a fixed mission.
int runBenchLoopCommand(int argc, char** argv);
/// `msbench bench-sim`: physics and rendering throughput figures.
int runBenchSimCommand(int argc, char** argv);

}  // namespace msb
