// The compute latency log of a run (compute_latency.csv, docs/compute.md): written beside
// metrics.json when compute is charged or modelled, read back by `timing.replay`.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "tools/engine/mission.h"

namespace msb {

/// The log's file name in a run's directory.
inline constexpr char kComputeLogFile[] = "compute_latency.csv";

/// Reads the log `spec.timing.replay` names into `spec.compute_replay` (nothing if it names
/// none). A missing, unreadable or truncated log, or one another build wrote, throws
/// InputFileError naming `label`, the key and the file: bad input, before anything is written.
void loadComputeReplay(ScenarioSpec& spec, const std::string& label);

/// `spec` as its run's config.yaml records it: a charged run replays from the log written beside
/// that file (timing.replay: compute_latency.csv).
inline ScenarioSpec runOwnComputeLog(ScenarioSpec spec) {
  if (spec.timing.compute == ComputeMode::kCharged) spec.timing.replay = kComputeLogFile;
  return spec;
}

/// metrics.json's `timing`: the mode, the model, the machine factor and per stage the calls, the
/// latency's median, p95 and mean (s) and the calls that waited for the method.
nlohmann::json computeTimingJson(const ScenarioSpec& spec, const MissionResult& r);

}  // namespace msb
