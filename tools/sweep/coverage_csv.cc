// Reading a run's coverage.csv for reports (strict: InputFileError naming file and line).
#include "tools/sweep/coverage_csv.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "core/common/strict_number.h"
#include "tools/results/input_files.h"
#include "tools/results/run_record.h"

namespace msb {

namespace fs = std::filesystem;

// coverage.csv rows by column name (older files without box_share read it as 0). Strict: the
// file present (a complete run writes one), a header with t_s, every row as many numbers as the
// header has names; else InputFileError naming the file and the line.
std::vector<CoverageSample> readCoverageCsv(const fs::path& file) {
  std::vector<CoverageSample> out;
  if (!fs::exists(fs::symlink_status(file)))
    throw InputFileError(file.string() + ": missing (every complete run writes one)");
  std::istringstream in(readInputFile(file));
  auto bad = [&](size_t line, const std::string& why) {
    return InputFileError(file.string() + ": line " + std::to_string(line) + ": " + why);
  };
  std::string line;
  if (!std::getline(in, line)) return out;
  std::vector<std::string> names;
  {
    std::istringstream h(line);
    for (std::string n; std::getline(h, n, ',');) names.push_back(n);
  }
  if (std::find(names.begin(), names.end(), "t_s") == names.end()) throw bad(1, "not a coverage.csv header (no t_s)");
  const std::map<std::string, double CoverageSample::*> fields = {
      {"t_s", &CoverageSample::t_s},
      {"area_m2", &CoverageSample::area_m2},
      {"area_box_m2", &CoverageSample::area_box_m2},
      {"area_true_frame_m2", &CoverageSample::area_gt_m2},
      {"distance_m", &CoverageSample::distance_m},
      {"box_share", &CoverageSample::box_share},
      {"area_verified_m2", &CoverageSample::area_verified_m2},
      {"score_earned_m3", &CoverageSample::score_earned_m3}};
  for (size_t n = 2; std::getline(in, line); ++n) {
    std::istringstream row(line);
    CoverageSample c;
    size_t k = 0;
    for (std::string v; std::getline(row, v, ','); ++k) {
      if (k >= names.size()) throw bad(n, "more values than the header has names");
      double x = 0;
      std::string why;
      if (!parseNumber(v, &x, &why)) throw bad(n, "column '" + names[k] + "': " + why);
      // Times, areas and distances are never negative (the earned score may be); a share is at most 1.
      if ((x < 0 && names[k] != "score_earned_m3") || (names[k] == "box_share" && x > 1) ||
          (names[k] != "t_s" && names[k] != "box_share" && std::abs(x) > kMaxAreaM2))
        throw bad(n, "column '" + names[k] + "': " + v + " is out of range");
      if (const auto f = fields.find(names[k]); f != fields.end()) c.*(f->second) = x;
    }
    if (k != names.size()) throw bad(n, "fewer values than the header has names");
    out.push_back(c);
  }
  return out;
}

}  // namespace msb
