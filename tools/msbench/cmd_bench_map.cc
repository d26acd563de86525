// msbench bench-map: the mapper's time per update over a perception log.
#include <cstdio>

#include "core/methods/monospheres/map/sphere_map.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/msbench/map_replay.h"
#include "tools/results/flight_records.h"

namespace msb {

int runBenchMapCommand(int argc, char** argv) {
  ArgParser args("msbench bench-map", "Per-update time of the mapper over a perception log.");
  args.positional("LOG", "perception log").option("map-rate-hz", "5", "map update rate");
  if (!args.parse(argc, argv)) return kExitOk;
  const double rate_hz = args.getDoubleIn("map-rate-hz", 0.01, 1000.0);
  const PerceptionLog log = readReplayableLog(args.get("LOG"));
  SphereMap map(SphereMapConfig{}, cameraFromHeader(args.get("LOG"), log.header), 1);
  const Replay r = replay(log, map, rate_hz);
  std::printf("bench-map: %zu updates over %.0f s; final %zu spheres, %zu obstacle points\n", r.stats.size(),
              r.t.empty() ? 0.0 : r.t.back(), map.spheres().size(), map.obstacles().size());
  std::printf("  update ms: median %.2f  p95 %.2f  p99 %.2f  max %.2f\n", percentile(r.total_ms, 0.5),
              percentile(r.total_ms, 0.95), percentile(r.total_ms, 0.99), percentile(r.total_ms, 1.0));
  const char* names[] = {"polyhedron", "dbof", "spheres", "sampling", "graph", "obstacles", "frontiers"};
  for (int k = 0; k < 7; ++k) {
    std::vector<double> v;
    for (const auto& s : r.stats) {
      const double ms[] = {s.polyhedron_ms, s.dbof_ms,      s.spheres_ms,  s.sampling_ms,
                           s.graph_ms,      s.obstacles_ms, s.frontiers_ms};
      v.push_back(ms[k]);
    }
    std::printf("  %-11s median %.3f  p99 %.3f ms\n", names[k], percentile(v, 0.5), percentile(v, 0.99));
  }
  return kExitOk;
}

}  // namespace msb
