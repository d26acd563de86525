// JSON result and data files msbench did not just write itself (metrics.json, sweep.json,
// goldens): read through readInputFile (core/common/input_file.h: regular files only, a size
// limit), then a nesting limit and duplicate keys refused. Errors name the file and the reason
// (docs/robustness.md).
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "core/common/input_file.h"

namespace msb {

/// `text` parsed as JSON: nesting deeper than `limits.max_depth` and a key twice in one object
/// are refused. `where` names the source in messages. Throws InputFileError.
nlohmann::json parseJsonStrict(const std::string& text, const std::string& where, const InputLimits& limits = {});

/// readInputFile + parseJsonStrict.
nlohmann::json readJsonFile(const std::filesystem::path& path, const InputLimits& limits = {});

}  // namespace msb
