// One closed-loop mission (`msbench run`): the scripted-flight loop of flight_runner with an
// exploration method in the loop (map updates, planning) and the coverage metric sampled at
// its rate, all on the integer tick clock (DESIGN §2, §10).
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/eval/column_coverage.h"
#include "core/planning/explorer.h"
#include "tools/msbench/flight_runner.h"
#include "tools/msbench/scenario_spec.h"

namespace msb {

/// One row of coverage.csv.
struct CoverageSample {
  double t_s = 0;
  double area_m2 = 0;          ///< unbounded, VIO frame (as the paper)
  double area_box_m2 = 0;      ///< columns whose node lies in the exploration box
  double area_gt_m2 = 0;       ///< unbounded, spheres mapped to the true frame when first seen
  double distance_m = 0;       ///< flown so far (ground truth)
};

/// Wall time per stage, summed over the mission (ms; recorded, never used).
struct StageTimes {
  double render_ms = 0, tracker_ms = 0, triangulation_ms = 0, map_ms = 0, planning_ms = 0, metric_ms = 0;
};

/// Everything a mission produced.
struct MissionResult {
  FlightResult flight;                     ///< status, collision, trajectory, timing
  std::vector<CoverageSample> coverage;    ///< at the metric rate
  ColumnCoverage columns;                  ///< explored columns (VIO frame)
  ColumnCoverage columns_gt;               ///< explored columns (true frame)
  ExplorerSnapshot final_map;              ///< the map at the end
  std::map<std::string, double> counters;  ///< the method's counters at the end
  StageTimes stages;
  std::vector<std::pair<double, StageTimes>> stage_timeline;  ///< cumulative, every 10 simulated s
  Aabb exploration_box;
  int box_explorable_columns = 0;          ///< 0 if the world has no ground truth
  uint64_t map_hash = 0;                   ///< FNV-1a over the final map snapshot
  uint64_t run_hash = 0;                   ///< trajectory + map + coverage
};

/// A progress report (once per simulated second).
using MissionProgress = std::function<void(double sim_s, double wall_s, double area_m2, const std::map<std::string, double>&)>;

/// Creates the exploration method named by spec.method_type.
std::unique_ptr<Explorer> makeExplorer(const ScenarioSpec& spec, const FisheyeCamera& camera,
                                       const ExplorerContext& context);

/// Runs the mission. `truth` (generated worlds) enables the box share; `spec.flight.world_path`
/// must be resolved and the start pose set. Throws std::runtime_error on setup failures.
/// `on_perception` (optional) sees every perception frame, e.g. to record a log for map-replay.
MissionResult runMission(const ScenarioSpec& spec, const Aabb& box, const WorldTruth* truth,
                         const MissionProgress& progress = {}, const PerceptionCallback& on_perception = {});

/// Hash of a map snapshot (free space, obstacles, frontiers).
uint64_t hashSnapshot(const ExplorerSnapshot& snap);

}  // namespace msb
