// Where a result comes from: library versions, the machine (for deciding whether two results
// must agree bit for bit), peak memory, and the hexadecimal form of the hashes.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace msb {

/// The git revision this binary was built from (12 hex digits, "-dirty" if the tracked files
/// differed from it; taken at build time by cmake/GitRevision.cmake).
const char* msbGitRevision();
/// Versions of the libraries a result depends on (MuJoCo, OpenCV, Eigen, msbench git revision).
nlohmann::json versionInfo();

/// The machine a result comes from, for deciding whether two results must agree bit for bit
/// (docs/regression.md): CPU model, a hash of its flags, compiler, MuJoCo, OpenCV and the GL
/// renderer (`gl_description`, e.g. "llvmpipe ... / 4.5 (Compat...) Mesa 22.3.6"), and "id", a
/// hash of all of them.
nlohmann::json machineFingerprint(const std::string& gl_description);

/// Peak resident memory of this process in MiB (VmHWM; 0 where /proc is unavailable).
double peakRssMb();

/// 16-digit hexadecimal form of a hash.
std::string hexHash(uint64_t h);

}  // namespace msb
