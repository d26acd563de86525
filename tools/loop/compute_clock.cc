#include "tools/loop/compute_clock.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/common/config_check.h"

namespace msb {

namespace {

// The reference workload's CPU time on the reference machine (s): the 2-core x86-64 VM that
// measured docs/compute.md, best of 5 (metrics.json timing.machine_workload_s of a charged run).
constexpr double kReferenceWorkloadS = 0.0174;

// The counters a term multiplies ("a*b" → {a, b}).
std::vector<std::string> termFactors(const std::string& term) {
  std::vector<std::string> out(1);
  for (char ch : term) {
    if (ch == '*')
      out.emplace_back();
    else
      out.back() += ch;
  }
  return out;
}

}  // namespace

void StageCostModel::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  for (const auto& [term, coef] : per) {
    c.require(std::isfinite(coef) && coef >= 0.0, "per." + term, "must be a finite number >= 0");
    for (const std::string& f : termFactors(term))
      c.require(!f.empty(), "per." + term,
                "a term is a counter or counters joined by '*' (e.g. frontiers*obstacle_points)");
  }
}

double StageCostModel::seconds(const std::map<std::string, double>& counters) const {
  double s = base_s;
  for (const auto& [term, coef] : per) {
    double product = coef;
    for (const std::string& f : termFactors(term)) {
      const auto it = counters.find(f);
      if (it == counters.end()) throw std::runtime_error("the method has no counter '" + f + "'");
      product *= it->second;
    }
    s += product;
  }
  return s;
}

void ComputeTiming::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require(compute_model == "none" || compute == "modelled", "compute_model",
            "names a cost model, which only compute: modelled uses");
  c.require(replay.empty() || compute == "charged", "replay", "replays charged latencies (compute: charged)");
}

void ComputeTiming::applyProfile() {
  if (compute_model != "reference_python") return;
  // The authors' Python stack (docs/compute.md, "The reference profile", how each was fitted).
  map = StageCostModel{0.114, {{"obstacle_points", 5.4e-6}, {"spheres", 6.9e-7}}};
  plan = StageCostModel{0.011, {{"frontiers", 1.44e-5}, {"spheres", 1.53e-5}}};
}

const char* stageName(ComputeCall::Stage s) { return s == ComputeCall::Stage::kMap ? "map" : "plan"; }

std::string computeLogText(const std::vector<ComputeCall>& calls, const std::string& build, const std::string& mode,
                           double machine_factor) {
  std::ostringstream out;
  out.precision(17);
  out << "# msbench compute latency log; build " << build << "; compute " << mode << "; machine_factor "
      << machine_factor << "\n";
  out << "call,stage,asked_tick,start_tick,cpu_ns,latency_ticks\n";
  for (size_t i = 0; i < calls.size(); ++i) {
    const ComputeCall& c = calls[i];
    out << i << ',' << stageName(c.stage) << ',' << c.asked_tick << ',' << c.start_tick << ',' << c.cpu_ns << ','
        << c.latency_ticks << '\n';
  }
  out << "# end; calls " << calls.size() << "\n";
  return out.str();
}

ComputeLog parseComputeLog(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  const std::string head = "# msbench compute latency log; build ";
  if (!std::getline(in, line) || line.rfind(head, 0) != 0) throw std::runtime_error("not a compute latency log");
  ComputeLog log;
  log.build = line.substr(head.size(), line.find(';', head.size()) - head.size());
  if (const size_t f = line.find("machine_factor "); f != std::string::npos) {
    try {
      log.machine_factor = std::stod(line.substr(f + 15));
    } catch (const std::exception&) {
      throw std::runtime_error("the header's machine_factor is not a number");
    }
  }
  if (!std::getline(in, line) || line != "call,stage,asked_tick,start_tick,cpu_ns,latency_ticks")
    throw std::runtime_error("line 2 is not the column header");
  std::vector<ComputeCall>& calls = log.calls;
  for (int n = 3; std::getline(in, line); ++n) {
    if (line.rfind("# end; calls ", 0) == 0) {
      if (line.substr(13) != std::to_string(calls.size()))
        throw std::runtime_error("the closing line counts " + line.substr(13) + " calls, the log has " +
                                 std::to_string(calls.size()));
      return log;
    }
    std::istringstream row(line);
    std::string f[6];
    for (auto& s : f) std::getline(row, s, ',');
    ComputeCall c;
    try {
      if (std::stoul(f[0]) != calls.size() || (f[1] != "map" && f[1] != "plan")) throw std::invalid_argument("");
      c.stage = f[1] == "map" ? ComputeCall::Stage::kMap : ComputeCall::Stage::kPlan;
      c.asked_tick = std::stoll(f[2]), c.start_tick = std::stoll(f[3]), c.cpu_ns = std::stoll(f[4]);
      c.latency_ticks = std::stoll(f[5]);
    } catch (const std::exception&) {
      throw std::runtime_error("line " + std::to_string(n) + " is not a call row: '" + line + "'");
    }
    if (c.latency_ticks < 0) throw std::runtime_error("line " + std::to_string(n) + ": a negative latency");
    calls.push_back(c);
  }
  throw std::runtime_error("truncated: no closing line after " + std::to_string(calls.size()) + " calls");
}

void checkModelTerms(const ComputeTiming& timing, const std::map<std::string, double>& counters,
                     const std::string& method) {
  if (timing.compute != "modelled") return;
  for (const auto* stage : {&timing.map, &timing.plan})
    for (const auto& [term, coef] : stage->per)
      for (const std::string& f : termFactors(term))
        if (!counters.count(f)) {
          std::string names;
          for (const auto& [name, v] : counters) names += (names.empty() ? "" : ", ") + name;
          throw ConfigError(std::string("timing.") + (stage == &timing.map ? "map" : "plan") + ".per." + term,
                            "method '" + method + "' has no counter '" + f + "' (it has: " + names + ")");
        }
}

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double measureMachineFactor() { return kReferenceWorkloadS / referenceWorkloadSeconds(); }

double referenceWorkloadSeconds() {
  // A fixed workload of the kind methods do: nearest neighbours by brute force over a cloud, then a
  // sort. Integer-seeded, no allocation inside the timed part beyond its vectors.
  auto workload = [] {
    uint64_t s = 0x9E3779B97F4A7C15ull;
    auto next = [&s] { return double((s = s * 6364136223846793005ull + 1442695040888963407ull) >> 11) * 0x1p-53; };
    std::vector<double> cloud(3 * 4000), keys(200000);
    for (double& x : cloud) x = next();
    for (double& k : keys) k = next();
    double sum = 0;
    for (int q = 0; q < 400; ++q) {
      const double qx = next(), qy = next(), qz = next();
      double best = 1e9;
      for (size_t i = 0; i < cloud.size(); i += 3) {
        const double dx = cloud[i] - qx, dy = cloud[i + 1] - qy, dz = cloud[i + 2] - qz;
        best = std::min(best, dx * dx + dy * dy + dz * dz);
      }
      sum += best;
    }
    std::sort(keys.begin(), keys.end());
    return sum + keys[keys.size() / 2];
  };
  double best = 1e9;
  volatile double sink = 0;
  for (int rep = 0; rep < 5; ++rep) {
    const double t0 = threadCpuSeconds();
    sink = sink + workload();
    best = std::min(best, threadCpuSeconds() - t0);
  }
  return std::max(best, 1e-6);
}

void ComputeClock::ask(ComputeCall::Stage s, int64_t tick) {
  std::optional<int64_t>& asked = s == ComputeCall::Stage::kMap ? map_asked_ : plan_asked_;
  if (!asked) asked = tick;
}

std::optional<ComputeCall> ComputeClock::next(int64_t tick) {
  // Busy past the next frame: the call waits for a later camera tick.
  if (busy_until_ >= tick + frame_ticks_ || (!map_asked_ && !plan_asked_)) return std::nullopt;
  const bool map_first = map_asked_ && (!plan_asked_ || *map_asked_ <= *plan_asked_);
  ComputeCall c;
  c.stage = map_first ? ComputeCall::Stage::kMap : ComputeCall::Stage::kPlan;
  std::optional<int64_t>& asked = map_first ? map_asked_ : plan_asked_;
  c.asked_tick = *asked;
  c.start_tick = std::max(tick, busy_until_);
  asked.reset();
  return c;
}

void ComputeClock::charge(ComputeCall& call, int64_t latency_ticks) {
  call.latency_ticks = latency_ticks;
  busy_until_ = call.start_tick + latency_ticks;
}

}  // namespace msb
