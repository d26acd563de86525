#include "sim/physics/mjcf_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/common/config_check.h"

namespace msb {

namespace fs = std::filesystem;

namespace {

constexpr off_t kMaxBytes = off_t(64) << 20;  // the largest generated world's MJCF is a few MB
constexpr size_t kMaxFiles = 256;

// One MJCF file's text. Opened without blocking and checked as opened (a FIFO or device is
// refused before a byte is read, and a file swapped after a check is still the one checked).
std::string readChecked(const std::string& path, const std::string& what) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0)
    throw ConfigError("world",
                      path + ": " + (errno == ENOENT ? what + " not found" : std::string(std::strerror(errno))));
  struct stat st {};
  std::string text;
  std::string problem;
  if (fstat(fd, &st) != 0)
    problem = std::strerror(errno);
  else if (!S_ISREG(st.st_mode))
    problem = "not a regular file (" + what + " must be an MJCF file)";
  else if (st.st_size > kMaxBytes)
    problem = "larger than 64 MiB, not a world file msbench can load";
  else if (st.st_size == 0)
    problem = "the " + what + " is empty";
  if (problem.empty()) {
    text.resize(size_t(st.st_size));
    size_t got = 0;
    while (got < text.size()) {
      const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      got += size_t(n);
    }
    if (got != text.size()) problem = "cannot read " + what;
  }
  ::close(fd);
  if (!problem.empty()) throw ConfigError("world", path + ": " + problem);
  return text;
}

// The `file` attribute of one element's text ("<include ... >"), or "" when it has none.
std::string fileAttribute(const std::string& element) {
  for (size_t at = element.find("file"); at != std::string::npos; at = element.find("file", at + 4)) {
    if (at == 0 || !std::isspace(static_cast<unsigned char>(element[at - 1]))) continue;
    size_t k = element.find_first_not_of(" \t\r\n", at + 4);
    if (k == std::string::npos || element[k] != '=') continue;
    k = element.find_first_not_of(" \t\r\n", k + 1);
    if (k == std::string::npos || (element[k] != '"' && element[k] != '\'')) continue;
    const size_t end = element.find(element[k], k + 1);
    if (end != std::string::npos) return element.substr(k + 1, end - k - 1);
  }
  return "";
}

// The `file` attributes of a text's <include> elements, XML comments skipped (a linear scan:
// world files are megabytes).
std::vector<std::string> includesOf(const std::string& xml) {
  std::vector<std::string> out;
  size_t pos = 0;
  while ((pos = xml.find('<', pos)) != std::string::npos) {
    if (xml.compare(pos, 4, "<!--") == 0) {
      const size_t end = xml.find("-->", pos + 4);
      if (end == std::string::npos) break;
      pos = end + 3;
      continue;
    }
    const size_t end = xml.find('>', pos);
    if (end == std::string::npos) break;
    if (xml.compare(pos, 8, "<include") == 0 && pos + 8 < xml.size() &&
        std::isspace(static_cast<unsigned char>(xml[pos + 8])))
      if (std::string file = fileAttribute(xml.substr(pos, end - pos)); !file.empty()) out.push_back(file);
    pos = end + 1;
  }
  return out;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> readMjcfFiles(const std::string& world_xml_path) {
  std::vector<std::pair<std::string, std::string>> files = {
      {world_xml_path, readChecked(world_xml_path, "world file")}};
  const fs::path dir = fs::absolute(world_xml_path).parent_path();
  std::vector<fs::path> seen = {fs::weakly_canonical(fs::absolute(world_xml_path))};
  // Breadth first over the includes; every path relative to the world file's directory.
  for (size_t i = 0; i < files.size(); ++i) {
    for (const std::string& name : includesOf(files[i].second)) {
      const fs::path path = fs::path(name).is_absolute() ? fs::path(name) : dir / name;
      const fs::path canonical = fs::weakly_canonical(path);
      if (std::find(seen.begin(), seen.end(), canonical) != seen.end())
        throw ConfigError("world", world_xml_path + ": " + files[i].first + " includes " + path.string() +
                                       ", which is already included (a cycle or a file twice)");
      if (files.size() >= kMaxFiles)
        throw ConfigError("world", world_xml_path + ": more than " + std::to_string(kMaxFiles) + " included files");
      seen.push_back(canonical);
      files.emplace_back(path.string(), readChecked(path.string(), "included file (of " + files[i].first + ")"));
    }
  }
  return files;
}

std::vector<std::string> mjcfInputFiles(const std::string& world_xml_path) {
  std::vector<std::string> paths;
  for (const auto& f : readMjcfFiles(world_xml_path)) paths.push_back(f.first);
  return paths;
}

}  // namespace msb
