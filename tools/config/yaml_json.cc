#include "tools/config/yaml_json.h"

#include <stdexcept>

#include <yaml-cpp/yaml.h>

namespace msb {

namespace {

// A scalar as what it reads as (yamlAsJson).
nlohmann::ordered_json scalarAsJson(const YAML::Node& n) {
  const std::string& s = n.Scalar();
  if (n.Tag() == "!") return s;  // quoted: a string whatever it looks like
  if (s == "~" || s == "null" || s.empty()) return nullptr;
  if (s == "true") return true;
  if (s == "false") return false;
  size_t used = 0;
  try {
    const long long i = std::stoll(s, &used);
    if (used == s.size()) return i;
  } catch (const std::exception&) {
  }
  try {
    const double d = std::stod(s, &used);
    if (used == s.size()) return d;
  } catch (const std::exception&) {
  }
  return s;
}

nlohmann::ordered_json nodeAsJson(const YAML::Node& n) {
  if (n.IsMap()) {
    nlohmann::ordered_json o = nlohmann::ordered_json::object();
    for (const auto& kv : n) o[kv.first.Scalar()] = nodeAsJson(kv.second);
    return o;
  }
  if (n.IsSequence()) {
    nlohmann::ordered_json a = nlohmann::ordered_json::array();
    for (const auto& e : n) a.push_back(nodeAsJson(e));
    return a;
  }
  if (n.IsScalar()) return scalarAsJson(n);
  return nullptr;
}

}  // namespace

nlohmann::ordered_json yamlAsJson(const std::string& yaml_text) {
  try {
    return nodeAsJson(YAML::Load(yaml_text));
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(std::string("not YAML: ") + e.what());
  }
}

}  // namespace msb
