// One run's entry in a sweep's index (sweep.json → runs[k]), as a struct with its JSON written
// and read in one place (docs/sweeps.md, "The sweep directory"): the runner writes it, the
// report reads it back strictly (a bad key names the file and the key). The words in the file
// are unchanged: "pending", "complete", "failed".
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace msb {

/// Where a run of a sweep stands.
enum class SweepRunStatus { kPending, kComplete, kFailed };

/// The word of a status in sweep.json and runs.csv.
const char* sweepRunStatusName(SweepRunStatus s);

/// Why a run has no result.
struct SweepRunFailure {
  int exit_code = 0;
  int signal = 0;             ///< the signal that ended it (0: it exited)
  std::string signal_name;    ///< "SIGSEGV", ... ("" for no signal)
  std::string log_tail;       ///< the end of its log
  std::string last_progress;  ///< its last progress line ("" if none)
  std::string fatal;          ///< the crash handler's line ("" if none)
  std::string problem;        ///< the report's: its results did not read ("" otherwise)
  std::string limit;          ///< the sweep stopped it: its wall-clock limit passed ("" otherwise)
};

/// One run's entry.
struct SweepRunRecord {
  std::string id;
  uint64_t seed = 0;
  std::string scenario;
  std::map<std::string, std::string> labels;  ///< axis name → label
  std::vector<std::string> sets;              ///< "key=value" overrides, in order
  SweepRunStatus status = SweepRunStatus::kPending;
  std::optional<SweepRunFailure> failure;  ///< failed runs
  std::optional<double> area_m2;           ///< complete runs: A
  std::string run_status;                  ///< complete runs: the mission's status word
};

/// The entry as sweep.json holds it.
nlohmann::json sweepRunJson(const SweepRunRecord& r);

/// Reads an entry strictly; `bad(key, why)` makes the error (naming the file) for a key under
/// `key_prefix` ("runs[3]") that is missing or has the wrong type.
SweepRunRecord readSweepRun(const nlohmann::json& j, const std::string& key_prefix,
                            const std::function<std::runtime_error(const std::string&, const std::string&)>& bad);

/// Why `dir`/runs/`id` is not the sweep's own run directory ("" if it is, or if nothing is there):
/// a link, or a directory that resolves outside the sweep's runs/ — a run of another sweep or
/// scenario is never reported as this one's.
std::string foreignRunDir(const std::filesystem::path& dir, const std::string& id);

}  // namespace msb
