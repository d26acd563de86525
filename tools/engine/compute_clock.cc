#include "tools/engine/compute_clock.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/common/config_check.h"
#include "core/common/strict_number.h"

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
  c.require(compute_model == ComputeModel::kNone || compute == ComputeMode::kModelled, "compute_model",
            "names a cost model, which only compute: modelled uses");
  c.require(replay.empty() || compute == ComputeMode::kCharged, "replay",
            "replays charged latencies (compute: charged)");
}

void ComputeTiming::applyProfile() {
  if (compute_model != ComputeModel::kReferencePython) return;
  // The authors' Python stack (docs/compute.md, "The reference profile", how each was fitted).
  map = StageCostModel{0.114, {{"obstacle_points", 5.4e-6}, {"spheres", 6.9e-7}}};
  plan = StageCostModel{0.011, {{"frontiers", 1.44e-5}, {"spheres", 1.53e-5}}};
}

namespace {
// The log's first words and its column header.
constexpr char kLogHead[] = "# msbench compute latency log";
constexpr char kLogColumns[] = "call,stage,asked_tick,start_tick,cpu_ns,latency_ticks";
}  // namespace

const char* stageName(ComputeCall::Stage s) { return s == ComputeCall::Stage::kMap ? "map" : "plan"; }

std::string computeLogText(const std::vector<ComputeCall>& calls, const ComputeLogHeader& h) {
  std::ostringstream out;
  out.precision(17);
  out << kLogHead << "; build " << h.build << "; compute " << h.mode << "; machine_factor " << h.machine_factor
      << "; seed " << h.seed << "; scenario " << h.scenario << "\n";
  out << kLogColumns << "\n";
  for (size_t i = 0; i < calls.size(); ++i) {
    const ComputeCall& c = calls[i];
    out << i << ',' << stageName(c.stage) << ',' << c.asked_tick << ',' << c.start_tick << ',' << c.cpu_ns << ','
        << c.latency_ticks << '\n';
  }
  out << "# end; calls " << calls.size() << "\n";
  return out.str();
}

namespace {

// The header's fields ("build B; compute M; machine_factor F; seed S; scenario H"), each once.
ComputeLogHeader parseLogHeader(const std::string& line) {
  if (line.rfind(kLogHead, 0) != 0) throw std::runtime_error("not a compute latency log");
  std::map<std::string, std::string> fields;
  for (size_t at = std::strlen(kLogHead); at < line.size();) {
    if (line.compare(at, 2, "; ") != 0) throw std::runtime_error("line 1: expected '; ' after the log's name");
    const size_t end = std::min(line.find("; ", at + 2), line.size());
    const std::string field = line.substr(at + 2, end - at - 2);
    const size_t space = field.find(' ');
    if (space == std::string::npos || !fields.emplace(field.substr(0, space), field.substr(space + 1)).second)
      throw std::runtime_error("line 1: field '" + field + "' is not a 'name value' pair, or is given twice");
    at = end;
  }
  for (const char* k : {"build", "compute", "machine_factor", "seed", "scenario"})
    if (!fields.count(k)) throw std::runtime_error(std::string("line 1: the header has no ") + k);
  if (fields.size() != 5) throw std::runtime_error("line 1: the header has fields msbench does not write");
  ComputeLogHeader h;
  h.build = fields["build"], h.mode = fields["compute"], h.scenario = fields["scenario"];
  std::string why;
  if (!parseNumber(fields["machine_factor"], &h.machine_factor, &why) || !(h.machine_factor > 0))
    throw std::runtime_error("line 1: machine_factor " +
                             (why.empty() ? "'" + fields["machine_factor"] + "' is not above 0" : why) +
                             " (a machine factor is a finite number above 0)");
  if (!parseUnsigned(fields["seed"], &h.seed, &why)) throw std::runtime_error("line 1: seed " + why);
  return h;
}

// One row's six fields, each its whole text, checked against the call before it.
ComputeCall parseLogRow(const std::string& line, int n, size_t index, const ComputeCall* prev, int64_t max_latency) {
  const std::string at = "line " + std::to_string(n) + " ('" + line + "'): ";
  std::vector<std::string> f;
  std::istringstream row(line);
  for (std::string s; std::getline(row, s, ',');) f.push_back(s);
  if (f.size() != 6 || line.back() == ',') throw std::runtime_error(at + "expected 6 comma-separated fields");
  int64_t v[5];
  std::string why;
  for (int k : {0, 2, 3, 4, 5})
    if (!parseInteger(f[size_t(k)], &v[k == 0 ? 0 : k - 1], &why) ||
        f[size_t(k)].find_first_of("+ \t") != std::string::npos)
      throw std::runtime_error(at + "field " + std::to_string(k + 1) + " " +
                               (why.empty() ? "'" + f[size_t(k)] + "' is not a plain integer" : why));
  ComputeCall c;
  if (v[0] != int64_t(index)) throw std::runtime_error(at + "the call's index is not " + std::to_string(index));
  if (f[1] != "map" && f[1] != "plan") throw std::runtime_error(at + "the stage is not map or plan");
  c.stage = f[1] == "map" ? ComputeCall::Stage::kMap : ComputeCall::Stage::kPlan;
  c.asked_tick = v[1], c.start_tick = v[2], c.cpu_ns = v[3], c.latency_ticks = v[4];
  if (c.asked_tick < 0 || c.start_tick < c.asked_tick)
    throw std::runtime_error(at + "a call starts before it was asked for, or at a negative tick");
  if (c.cpu_ns < 0) throw std::runtime_error(at + "a negative CPU time");
  if (c.latency_ticks < 0 || c.latency_ticks > max_latency)
    throw std::runtime_error(at + "the latency is outside 0..." + std::to_string(max_latency) + " ticks");
  if (prev && c.asked_tick < prev->asked_tick) throw std::runtime_error(at + "asked for before the call above it");
  if (prev && c.start_tick < prev->start_tick + prev->latency_ticks)
    throw std::runtime_error(at + "starts before the call above it ended (the method is one computer)");
  return c;
}

}  // namespace

ComputeLog parseComputeLog(const std::string& text, int64_t max_latency_ticks) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error("not a compute latency log");
  ComputeLog log;
  log.header = parseLogHeader(line);
  if (!std::getline(in, line) || line != kLogColumns) throw std::runtime_error("line 2 is not the column header");
  std::vector<ComputeCall>& calls = log.calls;
  for (int n = 3; std::getline(in, line); ++n) {
    if (line.rfind("# end; calls ", 0) == 0) {
      if (line.substr(13) != std::to_string(calls.size()))
        throw std::runtime_error("the closing line counts " + line.substr(13) + " calls, the log has " +
                                 std::to_string(calls.size()));
      if (std::getline(in, line))
        throw std::runtime_error("line " + std::to_string(n + 1) + ": text after the closing line");
      return log;
    }
    calls.push_back(parseLogRow(line, n, calls.size(), calls.empty() ? nullptr : &calls.back(), max_latency_ticks));
  }
  throw std::runtime_error("truncated: no closing line after " + std::to_string(calls.size()) + " calls");
}

void checkModelTerms(const ComputeTiming& timing, const std::map<std::string, double>& counters,
                     const std::string& method) {
  if (timing.compute != ComputeMode::kModelled) return;
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
