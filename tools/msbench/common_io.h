// Shared helpers of the msbench commands: world lookup, version strings, CSV/PNG/JSON output.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "core/common/messages.h"
#include "core/common/wall_time.h"
#include "tools/loop/closed_loop.h"
#include "tools/msbench/yaml_reader.h"

namespace msb {

/// Versions of the libraries a result depends on (MuJoCo, OpenCV, Eigen, msbench git revision).
nlohmann::json versionInfo();

/// The machine a result comes from, for deciding whether two results must agree bit for bit
/// (docs/regression.md): CPU model, a hash of its flags, compiler, MuJoCo, OpenCV and the GL
/// renderer (`gl_description`, e.g. "llvmpipe ... / 4.5 (Compat...) Mesa 22.3.6"), and "id", a
/// hash of all of them.
nlohmann::json machineFingerprint(const std::string& gl_description);

/// PNG bytes of a grey-scale frame.
std::string encodePng(const CameraFrame& frame);

/// trajectory.csv text.
std::string trajectoryCsv(const std::vector<TrajectoryRow>& rows);

/// imu.csv text.
std::string imuCsv(const std::vector<ImuSample>& samples);

/// A progress line for long flights on stderr every 10 simulated seconds with the real-time
/// factor and an ETA (never part of the results).
class ProgressLine {
 public:
  /// `command` prefixes the line; `duration_s` is the run's limit.
  ProgressLine(std::string command, double duration_s);
  /// Call after every tick; prints when a tick completes a tenth simulated second.
  void update(const TickRecord& tick, int physics_hz);

 private:
  std::string command_;
  double duration_s_;
  WallClock::time_point start_;
};

/// The q-quantile (0..1, nearest rank) of a sample; 0 for an empty one.
double percentile(std::vector<double> values, double q);

/// Peak resident memory of this process in MiB (VmHWM; 0 where /proc is unavailable).
double peakRssMb();

/// 16-digit hexadecimal form of a hash.
std::string hexHash(uint64_t h);

/// Builds what `build` returns (a loop, a mission); a ConfigError it throws (a world that does
/// not load, a start pose inside an obstacle) is re-thrown as FileConfigError naming `file`.
template <class Build>
auto buildNamingFile(const std::string& file, Build&& build) -> decltype(build()) {
  try {
    return build();
  } catch (const ConfigError& e) {
    throw FileConfigError(file + ": " + e.what());
  }
}

}  // namespace msb
