// A YAML text as a JSON tree, for the layers that must not include yaml-cpp (the Python module
// hands a factory's params and a scenario's effective configuration to Python through it).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace msb {

/// `yaml_text` as a JSON tree in its own key order: maps as objects, lists as arrays, and each
/// scalar as what it reads as — a quoted scalar a string; `~`, `null` and empty null; `true` /
/// `false` booleans; a whole integer an integer; a whole number a float; anything else a string.
/// Throws std::runtime_error on a syntax error (msbench's own texts have none).
nlohmann::ordered_json yamlAsJson(const std::string& yaml_text);

}  // namespace msb
