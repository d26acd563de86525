#include "tools/results/run_record.h"

#include "core/common/rng.h"
#include "tools/results/input_files.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace msb {

namespace {

// The value at a dotted key, or null when a step is missing.
const nlohmann::json* at(const nlohmann::json& j, const std::string& dotted) {
  const nlohmann::json* node = &j;
  std::istringstream steps(dotted);
  for (std::string step; std::getline(steps, step, '.');) {
    if (!node->is_object() || !node->contains(step)) return nullptr;
    node = &(*node)[step];
  }
  return node;
}

bool isHex16(const std::string& s) {
  if (s.size() != 16) return false;
  for (char c : s)
    if (!std::isxdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

}  // namespace

MissionRecordRead missionRecordOf(const nlohmann::json& m, const std::filesystem::path& file) {
  const std::string where = file.string() + ": ";
  auto problem = [&](const std::string& key, const std::string& why) {
    return MissionRecordRead{std::nullopt, where + "key '" + key + "': " + why};
  };
  if (!m.is_object()) return {std::nullopt, where + "not a JSON object"};
  // Types first: every key a reader relies on.
  const struct {
    const char* key;
    bool (nlohmann::json::*is)() const noexcept;
    const char* type;
  } kRequired[] = {{"status", &nlohmann::json::is_string, "a string"},
                   {"world", &nlohmann::json::is_string, "a string"},
                   {"method", &nlohmann::json::is_string, "a string"},
                   {"sim_time_s", &nlohmann::json::is_number, "a number"},
                   {"determinism_hash", &nlohmann::json::is_string, "a string"},
                   {"coverage", &nlohmann::json::is_object, "an object"},
                   {"coverage.area_m2", &nlohmann::json::is_number, "a number"}};
  const nlohmann::json* status = at(m, "status");
  const auto status_word = status && status->is_string() ? parseRunStatus(status->get<std::string>()) : std::nullopt;
  if (status_word && isErrorStatus(*status_word))
    return {std::nullopt, where + "the run ended in an error: " + m.value("error", std::string("(no message)"))};
  for (const auto& r : kRequired) {
    const nlohmann::json* v = at(m, r.key);
    if (!v) return problem(r.key, "missing");
    if (!(v->*r.is)()) return problem(r.key, std::string("expected ") + r.type);
  }
  MissionRecord rec;
  const auto parsed = parseRunStatus(m["status"].get<std::string>());
  if (!parsed) return problem("status", "unknown status '" + m["status"].get<std::string>() + "'");
  rec.status = *parsed;
  rec.area_m2 = m["coverage"]["area_m2"].get<double>();
  if (!(rec.area_m2 >= 0.0 && rec.area_m2 <= kMaxAreaM2))
    return problem("coverage.area_m2", "expected a number in [0, " + std::to_string(int(kMaxAreaM2)) + "] m²");
  if (const nlohmann::json* b = at(m, "coverage.box_share"); b && !b->is_null()) {
    if (!b->is_number() || b->get<double>() < 0.0 || b->get<double>() > 1.0)
      return problem("coverage.box_share", "expected a number in [0, 1] or null");
    rec.box_share = b->get<double>();
  }
  // Every other area and share a report reads: absent, null, or in range (a corrupt figure makes
  // the run count as failed instead of being averaged).
  for (const char* key :
       {"area_box_m2", "area_true_frame_m2", "verified_area_m2", "seen_area_m2", "area_published_rule_m2"})
    if (const nlohmann::json* v = at(m["coverage"], key); v && !v->is_null())
      if (!v->is_number() || !(v->get<double>() >= 0.0 && v->get<double>() <= kMaxAreaM2))
        return problem(std::string("coverage.") + key,
                       "expected a number in [0, " + std::to_string(int(kMaxAreaM2)) + "] m² or null");
  for (const char* key : {"verified_box_share", "box_share_true_frame"})
    if (const nlohmann::json* v = at(m["coverage"], key); v && !v->is_null())
      if (!v->is_number() || !(v->get<double>() >= 0.0 && v->get<double>() <= 1.0))
        return problem(std::string("coverage.") + key, "expected a number in [0, 1] or null");
  // The earned score (signed, m³): absent, null, or a finite number within the area bound.
  if (const nlohmann::json* v = at(m, "score.earned"); v && !v->is_null()) {
    if (!v->is_number() || !(std::abs(v->get<double>()) <= kMaxAreaM2))
      return problem("score.earned", "expected a number in [-1e7, 1e7] m³ or null");
    rec.earned_m3 = v->get<double>();
    // A score is at most the box's truly free volume: more is a record no run of msbench wrote.
    if (const nlohmann::json* box = at(m, "score.box_free_m3"); box && box->is_number())
      if (*rec.earned_m3 > box->get<double>() * (1.0 + 1e-9) + 1e-6)
        return problem("score.earned", "claims " + std::to_string(*rec.earned_m3) + " m³, more than the box's free " +
                                           std::to_string(box->get<double>()) + " m³ (score.box_free_m3)");
  }
  rec.sim_time_s = m["sim_time_s"].get<double>();
  rec.determinism_hash = m["determinism_hash"].get<std::string>();
  if (!isHex16(rec.determinism_hash)) return problem("determinism_hash", "expected 16 hexadecimal digits");
  if (const nlohmann::json* id = at(m, "machine.id")) {
    if (!id->is_string()) return problem("machine.id", "expected a string");
    rec.machine_id = id->get<std::string>();
  }
  rec.world = m["world"].get<std::string>();
  rec.method = m["method"].get<std::string>();
  rec.metrics = m;
  return {std::move(rec), ""};
}

std::string recordDigest(const nlohmann::json& metrics, const std::string& coverage_csv) {
  nlohmann::json content = metrics;
  content.erase("record_digest");
  const std::string text = content.dump() + "\n" + coverage_csv;
  char hex[32];
  std::snprintf(hex, sizeof(hex), "fnv1a64:%016llx",
                static_cast<unsigned long long>(fnv1a64(text.data(), text.size())));
  return hex;
}

MissionRecordRead readMissionRecord(const std::filesystem::path& file) {
  nlohmann::json m;
  try {
    m = readJsonFile(file);
  } catch (const InputFileError& e) {
    return {std::nullopt, e.what()};
  }
  MissionRecordRead read = missionRecordOf(m, file);
  // The seal: the record and its coverage.csv as msbench wrote them (records from before the
  // seal carry none and are read as before).
  if (read.record && m.contains("record_digest")) {
    const std::filesystem::path csv = file.parent_path() / "coverage.csv";
    std::string text;
    std::error_code ec;
    if (!std::filesystem::exists(std::filesystem::symlink_status(csv, ec)))
      return {std::nullopt, csv.string() + ": missing (every complete run writes one)"};
    try {
      text = readInputFile(csv);
    } catch (const InputFileError& e) {
      return {std::nullopt, e.what()};
    }
    if (!m["record_digest"].is_string() || m["record_digest"].get<std::string>() != recordDigest(m, text))
      return {std::nullopt, file.string() + ": key 'record_digest': the record or " + csv.string() +
                                " changed after msbench wrote them (tampered or edited): the run is not counted"};
  }
  return read;
}

}  // namespace msb
