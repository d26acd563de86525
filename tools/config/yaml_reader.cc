#include "tools/config/yaml_reader.h"

#include <algorithm>
#include <map>
#include <vector>

namespace msb {

namespace {

// rejectDuplicateKeys' walk; `visited` counts the nodes met so far (an alias at every use).
void rejectDuplicates(const YAML::Node& node, const std::string& label, const std::string& prefix, size_t& visited) {
  if (++visited > kMaxYamlNodes)
    throw FileConfigError(label + ": expands to more than " + std::to_string(kMaxYamlNodes) +
                          " YAML nodes (aliases counted at every use); refused as too large");
  if (node.IsSequence()) {
    size_t i = 0;
    for (const YAML::Node& element : node)
      rejectDuplicates(element, label, prefix + "[" + std::to_string(i++) + "]", visited);
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
    rejectDuplicates(kv.second, label, path, visited);
  }
}

}  // namespace

void rejectDuplicateKeys(const YAML::Node& node, const std::string& label, const std::string& prefix) {
  size_t visited = 0;
  rejectDuplicates(node, label, prefix, visited);
}

std::string closestName(const std::string& typo, const std::set<std::string>& names) {
  std::string best;
  size_t best_d = std::max<size_t>(2, typo.size() / 3) + 1;
  for (const std::string& n : names) {
    // Levenshtein distance, one row at a time.
    std::vector<size_t> row(n.size() + 1);
    for (size_t j = 0; j <= n.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= typo.size(); ++i) {
      size_t diag = row[0];
      row[0] = i;
      for (size_t j = 1; j <= n.size(); ++j) {
        const size_t up = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (typo[i - 1] == n[j - 1] ? 0 : 1)});
        diag = up;
      }
    }
    if (row[n.size()] < best_d) best_d = row[n.size()], best = n;
  }
  return best;
}

YAML::Node loadYamlFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw FileConfigError(path + ": file not found");
  if (fs::is_directory(path, ec)) throw FileConfigError(path + ": is a directory, not a YAML file");
  if (!fs::is_regular_file(path, ec)) throw FileConfigError(path + ": not a regular file (a YAML file is expected)");
  if (const auto bytes = fs::file_size(path, ec); !ec && bytes > kMaxYamlFileBytes)
    throw FileConfigError(path + ": " + std::to_string(bytes) + " bytes, larger than a YAML input may be (" +
                          std::to_string(kMaxYamlFileBytes) + ")");
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
