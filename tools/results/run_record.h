// A mission's metrics.json read back as a typed record, strictly: the one place the keys every
// reader needs are checked (report, sweep resume, regress). A file that is missing, truncated,
// not JSON, or lacks a key or has it mistyped gives a problem naming the file and the key, and the
// run then counts as failed — never as complete with A = 0.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "tools/engine/records.h"

namespace msb {

/// Largest area a record may claim (10 km², 160 times the largest world's ground): a larger one
/// is a damaged or forged file.
inline constexpr double kMaxAreaM2 = 1e7;

/// What readers of a finished run rely on.
struct MissionRecord {
  RunStatus status = RunStatus::kCompleted;
  double area_m2 = 0.0;             ///< coverage.area_m2
  std::optional<double> box_share;  ///< coverage.box_share (null: no exploration box)
  std::optional<double> earned_m3;  ///< score.earned (m³; null or absent: not scored)
  double sim_time_s = 0.0;
  std::string determinism_hash;  ///< 16 hex digits
  std::string machine_id;        ///< machine.id ("" in records written before it existed)
  std::string world, method;
  nlohmann::json metrics;  ///< the whole file, for everything else
};

/// The record of `metrics` read from `file` (for messages), or the first problem found:
/// "FILE: key 'coverage.area_m2': missing". An `error` record (a run that threw) is a problem too.
struct MissionRecordRead {
  std::optional<MissionRecord> record;
  std::string problem;
};

/// Checks and converts a parsed metrics.json.
MissionRecordRead missionRecordOf(const nlohmann::json& metrics, const std::filesystem::path& file);

/// Reads and checks a metrics.json file (missing, unreadable or not JSON: a problem). A record
/// that carries `record_digest` must match its own content and its coverage.csv beside it; a
/// changed figure is a problem ("changed after msbench wrote it"), so the run is not counted.
MissionRecordRead readMissionRecord(const std::filesystem::path& file);

/// The digest msbench seals a run's record with: FNV-1a 64 over metrics.json's content without
/// `record_digest` (compact, sorted keys) and coverage.csv's bytes, as "fnv1a64:<16 hex>". It
/// detects an edit, not a forger who recomputes it (a method cannot: docs/python.md).
std::string recordDigest(const nlohmann::json& metrics, const std::string& coverage_csv);

}  // namespace msb
