#include "tools/results/provenance.h"

#include <mujoco/mujoco.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

#include <opencv2/core.hpp>

#include "core/common/rng.h"

namespace msb {

nlohmann::json versionInfo() {
  return {{"msbench", MSB_VERSION},
          {"git_revision", msbGitRevision()},
          {"mujoco", mj_versionString()},
          {"opencv", CV_VERSION},
          {"eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
                        std::to_string(EIGEN_MINOR_VERSION)}};
}

nlohmann::json machineFingerprint(const std::string& gl_description) {
  // The first processor's model name and flags (all cores of a machine report the same).
  std::string model = "?", flags;
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string key = line.substr(0, colon);
    key.erase(key.find_last_not_of(" \t") + 1);
    const std::string value = colon + 2 <= line.size() ? line.substr(colon + 2) : "";
    if (key == "model name" && model == "?") model = value;
    if (key == "flags" && flags.empty()) flags = value;
    if (model != "?" && !flags.empty()) break;
  }
  nlohmann::json j = {{"cpu_model", model},
                      {"cpu_flags_hash", hexHash(fnv1a64(flags.data(), flags.size()))},
                      {"compiler", std::string("gcc-compatible ") + __VERSION__},
                      {"mujoco", mj_versionString()},
                      {"opencv", CV_VERSION},
                      {"gl", gl_description}};
  const std::string all = j.dump();
  j["id"] = hexHash(fnv1a64(all.data(), all.size()));
  return j;
}

double peakRssMb() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::strtod(line.c_str() + 6, nullptr) / 1024.0;  // kB
  return 0.0;
}

std::string hexHash(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace msb
