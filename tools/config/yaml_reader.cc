#include "tools/config/yaml_reader.h"

#include <map>

namespace msb {

void rejectDuplicateKeys(const YAML::Node& node, const std::string& label, const std::string& prefix) {
  if (node.IsSequence()) {
    size_t i = 0;
    for (const YAML::Node& element : node)
      rejectDuplicateKeys(element, label, prefix + "[" + std::to_string(i++) + "]");
    return;
  }
  if (!node.IsMap()) return;
  std::map<std::string, int> first_line;
  for (const auto& kv : node) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : "<complex key>";
    const std::string path = prefix.empty() ? key : prefix + "." + key;
    const int line = kv.first.Mark().line + 1;
    const auto [it, fresh] = first_line.emplace(key, line);
    if (!fresh)
      throw FileConfigError(label + ": key '" + path + "': given twice (lines " + std::to_string(it->second) + " and " +
                            std::to_string(line) + ")");
    rejectDuplicateKeys(kv.second, label, path);
  }
}

YAML::Node loadYamlFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw FileConfigError(path + ": file not found");
  if (fs::is_directory(path, ec)) throw FileConfigError(path + ": is a directory, not a YAML file");
  if (!fs::is_regular_file(path, ec)) throw FileConfigError(path + ": not a regular file (a YAML file is expected)");
  YAML::Node node;
  try {
    node = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw FileConfigError(path + ": YAML syntax error at line " + std::to_string(e.mark.line + 1) + ", column " +
                          std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
  rejectDuplicateKeys(node, path);
  return node;
}

}  // namespace msb
