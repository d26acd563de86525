#include "tools/results/compute_log.h"

#include <algorithm>
#include <cmath>

#include "tools/results/input_files.h"
#include "tools/results/provenance.h"

namespace msb {

void loadComputeReplay(ScenarioSpec& spec, const std::string& label) {
  if (spec.timing.replay.empty()) return;
  const std::string where = label + ": key 'timing.replay': " + spec.timing.replay;
  // Checked whole before the run starts: every row, then the run it was measured in.
  const int64_t max_latency = int64_t(std::ceil(kMaxLoggedLatencyS * spec.flight.physics.physics_hz));
  const auto otherBuild = [&](const std::string& build) {
    return InputFileError(where + ": written by build " + build + ", this is build " + msbGitRevision() +
                          " (charged latencies replay only on the build that measured them)");
  };
  std::string text;
  try {
    text = readInputFile(spec.timing.replay);
    spec.compute_replay = parseComputeLog(text, max_latency);
  } catch (const InputFileError& e) {
    throw InputFileError(label + ": key 'timing.replay': " + e.what());
  } catch (const std::runtime_error& e) {
    // Another build's log (an older header among them) is named as such, not by its format.
    const std::string head = "# msbench compute latency log; build ";
    if (text.rfind(head, 0) == 0) {
      const std::string build = text.substr(head.size(), text.find_first_of(";\n", head.size()) - head.size());
      if (build != msbGitRevision()) throw otherBuild(build);
    }
    throw InputFileError(where + ": " + e.what());
  }
  const ComputeLogHeader& h = spec.compute_replay.header;
  if (h.build != msbGitRevision()) throw otherBuild(h.build);
  if (h.mode != "charged")
    throw InputFileError(where + ": measured under compute " + h.mode + "; only a charged run's log replays");
  if (h.seed != spec.flight.seed)
    throw InputFileError(where + ": measured in a run of seed " + std::to_string(h.seed) + ", this run's seed is " +
                         std::to_string(spec.flight.seed) + " (a log replays only into the run it was measured in)");
  if (!spec.replay_settings_hash.empty() && h.scenario != spec.replay_settings_hash)
    throw InputFileError(where + ": measured under scenario settings " + h.scenario + ", this run's are " +
                         spec.replay_settings_hash + " (another scenario, or keys changed; docs/compute.md)");
}

namespace {

// The q-quantile (nearest rank) of sorted values.
double quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  const size_t i = size_t(std::ceil(q * double(sorted.size()))) - (q > 0 ? 1 : 0);
  return sorted[std::min(i, sorted.size() - 1)];
}

}  // namespace

nlohmann::json computeTimingJson(const ScenarioSpec& spec, const MissionResult& r) {
  nlohmann::json j = {{"compute", wordOf(spec.timing.compute)}};
  if (spec.timing.free()) return j;
  if (spec.timing.compute_model != ComputeModel::kNone) j["compute_model"] = wordOf(spec.timing.compute_model);
  if (spec.timing.compute == ComputeMode::kCharged) {
    j["machine_factor"] = r.compute_machine_factor;
    j["replayed"] = !spec.timing.replay.empty();
  }
  j["log"] = kComputeLogFile;
  const double tick_s = 1.0 / spec.flight.physics.physics_hz;
  for (const auto stage : {ComputeCall::Stage::kMap, ComputeCall::Stage::kPlan}) {
    std::vector<double> lat, cpu;
    double wait_s = 0;
    for (const ComputeCall& c : r.flight.compute_calls) {
      if (c.stage != stage) continue;
      lat.push_back(double(c.latency_ticks) * tick_s);
      cpu.push_back(1e-9 * double(c.cpu_ns));
      wait_s += double(c.start_tick - c.asked_tick) * tick_s;
    }
    std::sort(lat.begin(), lat.end());
    double sum = 0;
    for (double x : lat) sum += x;
    nlohmann::json s = {{"calls", lat.size()},
                        {"latency_median_s", quantile(lat, 0.5)},
                        {"latency_p95_s", quantile(lat, 0.95)},
                        {"latency_mean_s", lat.empty() ? 0.0 : sum / double(lat.size())},
                        {"busy_s", sum},
                        {"rate_hz", r.flight.sim_time_s > 0 ? double(lat.size()) / r.flight.sim_time_s : 0.0},
                        {"wait_mean_s", lat.empty() ? 0.0 : wait_s / double(lat.size())}};
    if (spec.timing.compute == ComputeMode::kCharged) {
      std::sort(cpu.begin(), cpu.end());
      s["cpu_median_s"] = quantile(cpu, 0.5);
      s["cpu_p95_s"] = quantile(cpu, 0.95);
    }
    j[stageName(stage)] = s;
  }
  return j;
}

}  // namespace msb
