// msbench bench-loop: the closed loop's cost per stage, per simulated second and per frame, for
// a fixed mission (a world's scenario, seed and duration: deterministic, so the same flight for
// the same build), one core. The figure to compare before and after a performance change
// (docs/performance.md). Writes nothing.
#include <cstdio>

#include "core/common/wall_time.h"
#include "core/geometry/world_truth.h"
#include "tools/config/scenario_yaml.h"
#include "tools/config/world_registry.h"
#include "tools/engine/mission.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/msbench/crash_handler.h"
#include "tools/msbench/interrupt.h"
#include "tools/results/provenance.h"

namespace msb {

int runBenchLoopCommand(int argc, char** argv) {
  const std::vector<std::string> sets = takeRepeatedOption(argc, argv, "set");
  ArgParser args("msbench bench-loop",
                 "Closed-loop cost per stage (wall ms per simulated second and per frame), real-time\n"
                 "factor and peak memory of a fixed mission: scenarios/missions/<WORLD>.yaml (or a\n"
                 "scenario file), its seed, --duration simulated seconds. Run it pinned to one core:\n"
                 "taskset -c 1 msbench bench-loop --world urban --set perception.threads=1 (missions'\n"
                 "default is the pipelined loop on two threads). --set KEY=VALUE\n"
                 "overrides a scenario key (e.g. render.cull_per_face=false).");
  args.option("world", "urban", "world: its mission scenarios/missions/<WORLD>.yaml")
      .option("scenario", "", "a scenario file instead of --world")
      .option("duration", "60", "simulated seconds")
      .option("seed", "1", "seed");
  if (!args.parse(argc, argv)) return kExitOk;
  const std::string file = !args.get("scenario").empty()
                               ? args.get("scenario")
                               : std::string(MSB_MISSIONS_DIR) + "/" + args.get("world") + ".yaml";
  std::vector<std::string> all_sets = sets;
  all_sets.push_back("duration_s=" + args.get("duration"));
  all_sets.push_back("seed=" + args.get("seed"));
  all_sets.push_back("mission.progress=false");
  ScenarioSpec spec = loadScenario(file, all_sets);
  MissionWorld world = prepareMissionWorld(file, spec);
  const Aabb& box = world.box;
  std::optional<WorldTruth>& truth = world.truth;
  Mission mission = buildNamingFile(file, [&] { return Mission(spec, box, truth ? &*truth : nullptr); });
  while (mission.running()) {
    throwIfInterrupted();
    const TickRecord& t = mission.step();
    setCrashContext(t.tick, t.t_s);
  }
  const MissionResult r = mission.finish();
  const FlightResult& f = r.flight;
  const double sim = std::max(f.sim_time_s, 1e-9), frames = std::max<double>(f.frames_rendered, 1);
  const StageTimes& s = r.stages;
  const double total = f.wall_time_s * 1000.0;
  std::printf("bench-loop %s seed %s: %.0f s simulated, %ld frames, %s; wall %.1f s, RTF %.2f, peak RSS %.0f MiB\n",
              spec.name.c_str(), args.get("seed").c_str(), f.sim_time_s, long(f.frames_rendered),
              runStatusName(f.status), f.wall_time_s, f.realTimeFactor(), peakRssMb());
  std::printf("%-14s %12s %12s %8s\n", "stage", "ms/sim-s", "ms/frame", "share");
  auto row = [&](const char* name, double ms) {
    std::printf("%-14s %12.1f %12.2f %7.1f%%\n", name, ms / sim, ms / frames, 100.0 * ms / std::max(total, 1e-9));
  };
  if (f.threads == 1) {
    row("render", s.render_ms);
    row("tracker", s.tracker_ms);
    row("triangulation", s.triangulation_ms);
    row("map", s.map_ms);
    row("planning", s.planning_ms);
    row("metric", s.metric_ms);
    row("other", s.otherMs(total, f.threads, f.perception_wait_ms));
  } else {
    // The pipelined loop: the perception stages overlap the loop thread's work.
    std::printf("second thread (perception jobs):\n");
    row("  tracker", s.tracker_ms);
    row("  triangulation", s.triangulation_ms);
    row("  map", s.map_ms);
    row("  planning", s.planning_ms);
    std::printf("loop thread:\n");
    row("  render", s.render_ms);
    row("  metric", s.metric_ms);
    row("  waiting", f.perception_wait_ms);
    row("  other", s.otherMs(total, f.threads, f.perception_wait_ms));
  }
  row("total", total);
  std::printf("collision detection in %lld of %lld physics steps (physics.contact_gate)\n",
              static_cast<long long>(f.collision_detection_steps), static_cast<long long>(f.ticks));
  std::printf("determinism hash %s (same build and machine: the same flight)\n", hexHash(r.run_hash).c_str());
  return kExitOk;
}

}  // namespace msb
