// Files of a flight's records: trajectory.csv, imu.csv, frames as PNG; and the quantile used by
// the per-stage time summaries.
#pragma once

#include <string>
#include <vector>

#include "core/common/messages.h"
#include "tools/engine/closed_loop.h"
#include "tools/results/output_files.h"

namespace msb {

/// PNG bytes of a grey-scale frame.
std::string encodePng(const CameraFrame& frame);

/// trajectory.csv text.
std::string trajectoryCsv(const std::vector<TrajectoryRow>& rows);

/// imu.csv text.
std::string imuCsv(const std::vector<ImuSample>& samples);

/// Everything a scripted flight (`fly`, `vio-eval`) reads that its outputs must not overlap: the
/// flight file, an MJCF world file it names and the files that world includes.
std::vector<NamedPath> flightInputs(const std::string& flight_file, const FlightSpec& spec);
/// Adds an MJCF world file `spec` names (not a generated world) and every file it includes,
/// each checked as the loader checks it (sim/physics/mjcf_files.h; throws ConfigError).
void addWorldInputs(std::vector<NamedPath>& in, const FlightSpec& spec);

/// The q-quantile (0..1, nearest rank) of a sample; 0 for an empty one.
double percentile(std::vector<double> values, double q);

}  // namespace msb
