#include "tools/results/compute_log.h"

#include <algorithm>
#include <cmath>

#include "tools/results/input_files.h"
#include "tools/results/provenance.h"

namespace msb {

void loadComputeReplay(ScenarioSpec& spec, const std::string& label) {
  if (spec.timing.replay.empty()) return;
  const std::string where = label + ": key 'timing.replay': " + spec.timing.replay;
  try {
    spec.compute_replay = parseComputeLog(readInputFile(spec.timing.replay));
  } catch (const InputFileError& e) {
    throw InputFileError(label + ": key 'timing.replay': " + e.what());
  } catch (const std::runtime_error& e) {
    throw InputFileError(where + ": " + e.what());
  }
  if (spec.compute_replay.build != msbGitRevision())
    throw InputFileError(where + ": written by build " + spec.compute_replay.build + ", this is build " +
                         msbGitRevision() + " (charged latencies replay only on the build that measured them)");
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
  nlohmann::json j = {{"compute", spec.timing.compute}};
  if (spec.timing.free()) return j;
  if (spec.timing.compute_model != "none") j["compute_model"] = spec.timing.compute_model;
  if (spec.timing.compute == "charged") {
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
    if (spec.timing.compute == "charged") {
      std::sort(cpu.begin(), cpu.end());
      s["cpu_median_s"] = quantile(cpu, 0.5);
      s["cpu_p95_s"] = quantile(cpu, 0.95);
    }
    j[stageName(stage)] = s;
  }
  return j;
}

}  // namespace msb
