// Shared helpers of the msbench commands: world lookup, version strings, CSV/PNG/JSON output.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "core/common/messages.h"
#include "tools/msbench/flight_runner.h"

namespace msb {

/// Versions of the libraries a result depends on (MuJoCo, OpenCV, Eigen, msbench git revision).
nlohmann::json versionInfo();

/// PNG bytes of a grey-scale frame.
std::string encodePng(const CameraFrame& frame);

/// trajectory.csv text.
std::string trajectoryCsv(const std::vector<TrajectoryRow>& rows);

/// imu.csv text.
std::string imuCsv(const std::vector<ImuSample>& samples);

/// A progress printer for long flights: a line on stderr every 10 simulated seconds with the
/// real-time factor and an ETA (never part of the results).
ProgressCallback progressPrinter(const std::string& command, double duration_s);

/// The q-quantile (0..1, nearest rank) of a sample; 0 for an empty one.
double percentile(std::vector<double> values, double q);

/// 16-digit hexadecimal form of a hash.
std::string hexHash(uint64_t h);

}  // namespace msb
