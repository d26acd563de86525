// A run's coverage.csv as the report reads it.
#pragma once

#include <filesystem>
#include <vector>

#include "core/eval/coverage_sample.h"

namespace msb {

/// coverage.csv rows by column name (older files without box_share read it as 0). Strict: the
/// file present (a complete run writes one), a header with t_s, every row as many numbers as the
/// header has names; else InputFileError naming the file and the line.
std::vector<CoverageSample> readCoverageCsv(const std::filesystem::path& file);

}  // namespace msb
