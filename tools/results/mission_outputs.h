// The files of one mission (docs/architecture.md §3, §10): metrics.json, coverage.csv, timing.csv,
// trajectory.csv, map.ply and topdown.png.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "core/geometry/world_truth.h"
#include "tools/engine/mission.h"
#include "tools/results/output_files.h"

namespace msb {

/// Most counters a record keeps of a method's (the method writes them: a record must not carry
/// what it saw, e.g. a map as thousands of counters), and the longest name kept.
inline constexpr size_t kMaxRecordedCounters = 64;
inline constexpr size_t kMaxCounterNameBytes = 64;

/// metrics.json `counters`: the first kMaxRecordedCounters of `counters` in name order, names cut
/// to kMaxCounterNameBytes, non-finite values as null (`counters_dropped` says how many were left).
nlohmann::json recordedCounters(const std::map<std::string, double>& counters);

/// metrics.json content. `truth` (generated worlds, may be null) names the collided object and
/// its kind (textured, textureless, thin, ground).
nlohmann::json missionMetrics(const ScenarioSpec& spec, const MissionResult& r, const WorldTruth* truth);
/// metrics.json's `frontend_profile` (also vio-eval's summary.json).
nlohmann::json frontEndProfileJson(const FrontEndProfile& p);
/// coverage.csv text (t, A unbounded, A in box, A true frame, distance).
std::string coverageCsv(const std::vector<CoverageSample>& samples);
/// timing.csv text: cumulative wall time per stage every 10 simulated seconds.
std::string timingCsv(const MissionResult& r);
/// map.ply text: free-space spheres (kind 0, radius), obstacle points (1), frontiers (2).
std::string mapPly(const ExplorerSnapshot& snap);
/// Writes the top-down picture: explored columns, spheres, obstacle points, frontiers,
/// viewpoints and visited markers, the true and estimated trajectories, the box, a collision;
/// under them (faint) the ground-truth obstacles by kind when `truth` is given; axes in metres
/// and a scale bar.
/// The top-down picture as a BGR image (what writeTopdown encodes): when the run ended in a
/// collision and `truth` is given, the geom hit is outlined in red on top of the map, with the
/// contact point and a label (name, kind, height).
cv::Mat topdownImage(const MissionResult& r, const WorldTruth* truth);
/// Writes topdownImage() as a PNG.
void writeTopdown(const std::filesystem::path& file, const MissionResult& r, const WorldTruth* truth);

/// config.yaml text: the effective configuration of `scenario_file`, headed by where it came from,
/// or, when `not_replayable` gives a reason, by that reason (the file then does not claim to
/// reproduce the run).
std::string configYamlText(const std::string& scenario_file, bool with_overrides, const std::string& effective_yaml,
                           const std::string& not_replayable = "");

/// Writes a finished mission's result files into `dir` (coverage.csv, trajectory.csv, timing.csv,
/// map.ply when the scenario asks for it, topdown.png, metrics.json last) and returns metrics.json's
/// content. What `msbench run` and the Python module write alike. `extra`, called after every
/// file but metrics.json (a run's video finishes there), returns keys metrics.json gains before
/// it is sealed.
nlohmann::json writeMissionOutputs(const std::filesystem::path& dir, const ScenarioSpec& spec, const MissionResult& r,
                                   const WorldTruth* truth, const std::function<nlohmann::json()>& extra = nullptr);

/// Everything a mission reads that its outputs must not overlap: the scenario file, its `base:`
/// chain, an MJCF world file, and `extra` (e.g. a Python method's module file).
std::vector<NamedPath> missionInputs(const std::string& scenario_file, const ScenarioSpec& spec,
                                     const std::vector<NamedPath>& extra = {});

/// metrics.json of a run that ended in an error (its status, the message, seed, versions).
nlohmann::json errorMetrics(const ScenarioSpec& spec, const std::string& what, RunStatus status = RunStatus::kError);

/// Writes what a run that ended in an error (`what`, at `error_tick`) flew up to it: the files of
/// writeMissionOutputs from `mission` finished where it stopped, with status `error`, the message
/// and the tick in metrics.json (`error_tick` < 0: the last tick flown). If the mission cannot be finished (its method
/// fails again), only errorMetrics. `status`: error, or how a method's own process failed
/// (method_timeout, method_exited). Returns metrics.json's content.
nlohmann::json writeErroredMissionOutputs(const std::filesystem::path& dir, const ScenarioSpec& spec, Mission& mission,
                                          const std::string& what, int64_t error_tick, const WorldTruth* truth,
                                          RunStatus status = RunStatus::kError);

}  // namespace msb
