// Compute in the loop (docs/compute.md): a method's map updates and planning steps take simulated
// time. Under `timing.compute: free` (the default) they take none, as the loop always had it.
// Under `charged` each call's thread CPU time (plus the CPU time of the process a Python method
// runs in), scaled by a machine factor measured at start, becomes its latency; under `modelled`
// the latency is a deterministic function of the method's own work counters. The method is one
// computer: its calls run one at a time, in the order they were asked for; a call asked for while
// the method is busy waits, and the output of a planning step takes effect when the step ends.
// Every latency is logged; a charged run replays bit for bit from its log (`timing.replay`).
#pragma once

#include <array>
#include <climits>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/common/config_fields.h"

namespace msb {

/// A stage's cost under `modelled`: base_s + Σ coefficient × term, where a term is a method
/// counter ("obstacle_points") or a product of counters ("frontiers*obstacle_points"), read after
/// the call.
struct StageCostModel {
  double base_s = 0.0;                ///< seconds every call costs
  std::map<std::string, double> per;  ///< term → seconds per unit (read outside the key tables)

  /// The keys with a table (base_s; `per` is read as a map in tools/config).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("base_s", s.base_s, Limits::range(0.0, 3600.0));
  }
  /// Records invalid fields (a negative or non-finite coefficient, an empty term).
  void validate(ConfigChecker& c) const;
  /// The latency (s) of a call given the method's counters after it; throws std::runtime_error
  /// naming a counter the method does not have.
  double seconds(const std::map<std::string, double>& counters) const;
  bool operator==(const StageCostModel&) const = default;
};

/// How a method's computation takes simulated time (`timing.compute`, docs/compute.md).
enum class ComputeMode { kFree, kCharged, kModelled };
/// The words of ComputeMode (core/common/word_enum.h).
constexpr auto wordsOf(ComputeMode) {
  return std::array{std::pair{ComputeMode::kFree, "free"}, std::pair{ComputeMode::kCharged, "charged"},
                    std::pair{ComputeMode::kModelled, "modelled"}};
}

/// The profile of coefficients a modelled cost starts from (`timing.compute_model`).
enum class ComputeModel { kNone, kReferencePython };
/// The words of ComputeModel.
constexpr auto wordsOf(ComputeModel) {
  return std::array{std::pair{ComputeModel::kNone, "none"},
                    std::pair{ComputeModel::kReferencePython, "reference_python"}};
}

/// The `timing` section of a scenario: how a method's computation is charged. A suite-fixed
/// setting (it decides what a score means).
struct ComputeTiming {
  ComputeMode compute = ComputeMode::kFree;
  /// modelled: a profile of coefficients taken before the model's own keys (none, or
  /// reference_python: the authors' Python stack, docs/compute.md).
  ComputeModel compute_model = ComputeModel::kNone;
  StageCostModel map;   ///< modelled: a map update's cost
  StageCostModel plan;  ///< modelled: a planning step's cost
  /// charged: the latency log of an earlier run to replay instead of measuring (absolute after
  /// loading; "" = measure). Not a fixed setting.
  std::string replay;

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("compute", s.compute);
    v.key("compute_model", s.compute_model);
    v.group("map", s.map);
    v.group("plan", s.plan);
  }
  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
  /// Takes the coefficients of the profile named by compute_model (before named keys).
  void applyProfile();
  bool free() const { return compute == ComputeMode::kFree; }
  bool operator==(const ComputeTiming&) const = default;
};

/// One call of a method's stage as it was charged.
struct ComputeCall {
  enum class Stage { kMap, kPlan };
  Stage stage = Stage::kMap;
  int64_t asked_tick = 0;  ///< when the loop asked for it (its schedule)
  int64_t start_tick = 0;  ///< when it started (the method was free)
  int64_t cpu_ns = 0;      ///< charged: CPU time it took (0 otherwise)
  int64_t latency_ticks = 0;
};

/// The stage's name in logs and metrics ("map", "plan").
const char* stageName(ComputeCall::Stage s);

/// What a latency log's header names: the run it was measured in.
struct ComputeLogHeader {
  std::string build;            ///< the build that measured it (msbGitRevision)
  std::string mode;             ///< the timing.compute mode ("charged")
  double machine_factor = 1.0;  ///< finite, > 0
  uint64_t seed = 0;            ///< the run's seed
  std::string scenario;         ///< the run's replaySettingsHash (16 hex digits)
};

/// The latency log of a run (compute_latency.csv): a header naming build, mode, machine factor,
/// seed and scenario, one row per call, a closing line with the count (a truncated log lacks it).
std::string computeLogText(const std::vector<ComputeCall>& calls, const ComputeLogHeader& header);
/// A parsed latency log.
struct ComputeLog {
  ComputeLogHeader header;
  std::vector<ComputeCall> calls;
};
/// Largest latency a log may hold for one call (s): a call longer than an hour is no measurement.
inline constexpr double kMaxLoggedLatencyS = 3600.0;
/// Parses a latency log whole and strictly (every number its whole field, docs/compute.md
/// "Replays"): the header's five fields (machine factor finite and > 0), each row's six fields
/// — the call's index, its stage, asks non-decreasing, a start at or after its ask and after the
/// previous call's end (one computer), CPU time >= 0, a latency within 0...`max_latency_ticks` —
/// and a closing line whose count agrees. Throws std::runtime_error naming the line and reason.
ComputeLog parseComputeLog(const std::string& text, int64_t max_latency_ticks = INT64_MAX / 4);

/// Throws ConfigError (timing.map.per / timing.plan.per) for a term naming a counter that
/// `counters` (a method's work counters) lacks.
void checkModelTerms(const ComputeTiming& timing, const std::map<std::string, double>& counters,
                     const std::string& method);

/// CPU time of the calling thread (s).
double threadCpuSeconds();
/// The machine factor of `charged`: a fixed reference workload's CPU time on the reference
/// machine (docs/compute.md) over its CPU time here, the best of a few repetitions.
double measureMachineFactor();
/// The reference workload's CPU time here (s), best of 5.
double referenceWorkloadSeconds();

/// The method's computer: which asked-for calls start on a camera tick, and when each ends.
class ComputeClock {
 public:
  /// `frame_ticks`: ticks between camera frames (calls start on camera ticks or chain within one).
  explicit ComputeClock(int64_t frame_ticks) : frame_ticks_(frame_ticks) {}
  /// The loop asks for a stage's call on this tick (its schedule is due); asking again before it
  /// ran keeps the first ask.
  void ask(ComputeCall::Stage s, int64_t tick);
  /// The next call to start on camera tick `tick` (the oldest ask; map before plan on a tie) if
  /// the method is free before the next frame; none otherwise. The call starts at
  /// max(tick, the end of the previous call).
  std::optional<ComputeCall> next(int64_t tick);
  /// Ends `call` `latency_ticks` after its start (the method is busy until then).
  void charge(ComputeCall& call, int64_t latency_ticks);
  /// The tick the method is busy until.
  int64_t busyUntil() const { return busy_until_; }

 private:
  int64_t frame_ticks_ = 1, busy_until_ = 0;
  std::optional<int64_t> map_asked_, plan_asked_;
};

}  // namespace msb
