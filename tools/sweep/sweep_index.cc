#include "tools/sweep/sweep_index.h"

namespace msb {

const char* sweepRunStatusName(SweepRunStatus s) {
  switch (s) {
    case SweepRunStatus::kPending:
      return "pending";
    case SweepRunStatus::kComplete:
      return "complete";
    case SweepRunStatus::kFailed:
      return "failed";
  }
  return "pending";
}

nlohmann::json sweepRunJson(const SweepRunRecord& r) {
  nlohmann::json j = {{"id", r.id},
                      {"seed", r.seed},
                      {"scenario", r.scenario},
                      {"labels", r.labels},
                      {"status", sweepRunStatusName(r.status)}};
  j["sets"] = r.sets;
  if (r.failure) {
    const SweepRunFailure& f = *r.failure;
    j["failure"] = {{"exit_code", f.exit_code}, {"signal", f.signal}, {"log_tail", f.log_tail}};
    if (f.signal) j["failure"]["signal_name"] = f.signal_name;
    if (!f.last_progress.empty()) j["failure"]["last_progress"] = f.last_progress;
    if (!f.fatal.empty()) j["failure"]["fatal"] = f.fatal;
    if (!f.problem.empty()) j["failure"]["problem"] = f.problem;
    if (!f.limit.empty()) j["failure"]["limit"] = f.limit;
  }
  if (r.area_m2) j["area_m2"] = *r.area_m2, j["run_status"] = r.run_status;
  return j;
}

namespace {

// A failure record: known keys with their types; others are kept out.
SweepRunFailure readFailure(const nlohmann::json& f, const std::string& key,
                            const std::function<std::runtime_error(const std::string&, const std::string&)>& bad) {
  if (!f.is_object()) throw bad(key, "expected an object");
  SweepRunFailure out;
  auto integer = [&](const char* k, int& v) {
    if (!f.contains(k)) return;
    if (!f[k].is_number_integer()) throw bad(key + "." + k, "expected an integer");
    v = f[k].get<int>();
  };
  auto text = [&](const char* k, std::string& v) {
    if (!f.contains(k)) return;
    if (!f[k].is_string()) throw bad(key + "." + k, "expected a string");
    v = f[k].get<std::string>();
  };
  integer("exit_code", out.exit_code);
  integer("signal", out.signal);
  text("signal_name", out.signal_name);
  text("log_tail", out.log_tail);
  text("last_progress", out.last_progress);
  text("fatal", out.fatal);
  text("problem", out.problem);
  text("limit", out.limit);
  return out;
}

}  // namespace

SweepRunRecord readSweepRun(const nlohmann::json& jr, const std::string& key,
                            const std::function<std::runtime_error(const std::string&, const std::string&)>& bad) {
  if (!jr.is_object()) throw bad(key, "expected an object");
  if (!jr.contains("id") || !jr["id"].is_string() || jr["id"].get<std::string>().empty() ||
      jr["id"].get<std::string>().find('/') != std::string::npos)
    throw bad(key + ".id", "expected a run id (a non-empty name without '/')");
  SweepRunRecord r;
  r.id = jr["id"].get<std::string>();
  if (jr.contains("seed") && !jr["seed"].is_number_unsigned())
    throw bad(key + ".seed", "expected a non-negative integer");
  r.seed = jr.value("seed", uint64_t(0));
  if (jr.contains("scenario") && jr["scenario"].is_string()) r.scenario = jr["scenario"].get<std::string>();
  if (jr.contains("status") && !jr["status"].is_string())
    throw bad(key + ".status", "expected complete, failed or pending");
  const std::string status = jr.value("status", std::string("pending"));
  if (status == "complete")
    r.status = SweepRunStatus::kComplete;
  else if (status == "failed")
    r.status = SweepRunStatus::kFailed;
  else if (status == "pending")
    r.status = SweepRunStatus::kPending;
  else
    throw bad(key + ".status", "expected complete, failed or pending, got '" + status + "'");
  if (jr.contains("labels")) {
    if (!jr["labels"].is_object()) throw bad(key + ".labels", "expected a map of axis names to labels");
    for (const auto& [axis, label] : jr["labels"].items()) {
      if (!label.is_string()) throw bad(key + ".labels." + axis, "expected a label");
      r.labels[axis] = label.get<std::string>();
    }
  }
  if (jr.contains("sets") && jr["sets"].is_array())
    for (const auto& s : jr["sets"])
      if (s.is_string()) r.sets.push_back(s.get<std::string>());
  if (jr.contains("failure")) r.failure = readFailure(jr["failure"], key + ".failure", bad);
  if (jr.contains("area_m2") && jr["area_m2"].is_number()) r.area_m2 = jr["area_m2"].get<double>();
  if (jr.contains("run_status") && jr["run_status"].is_string()) r.run_status = jr["run_status"].get<std::string>();
  return r;
}

std::string foreignRunDir(const std::filesystem::path& dir, const std::string& id) {
  namespace fs = std::filesystem;
  const fs::path rd = dir / "runs" / id;
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(rd, ec);
  if (ec || !fs::exists(st)) return "";  // absent: the record's reading names it
  if (fs::is_symlink(st))
    return "runs/" + id + " is a link (to " + fs::read_symlink(rd, ec).string() +
           "), not a run directory of this sweep; left out";
  const fs::path real = fs::canonical(rd, ec), runs = fs::canonical(dir / "runs", ec);
  if (ec || real.parent_path() != runs)
    return "runs/" + id + " resolves to " + real.string() + ", outside this sweep's runs/; left out";
  return "";
}

}  // namespace msb
