// Recorded perception streams ("vio-eval --record LOG"): per camera frame the estimated camera
// pose, the ground-truth camera pose and the SLAM points, so the mapper can be replayed and
// benchmarked without simulating. Binary, little-endian, versioned by the magic bytes:
//   "MSBLOG2\n", one JSON header line (world, seed, camera config), then frames, each
//   u32 payload length, the payload, u64 FNV-1a checksum of the payload; the payload is
//   int64 tick, f64 t, 7×f64 T_W_C estimate (t, q wxyz), 7×f64 T_W_C truth, u32 n,
//   n × { u64 track id, 3×f64 p_W, 6×f64 covariance (xx xy xz yy yz zz), f64 depth, f64 depth σ,
//         i64 anchor tick, 2×f64 anchor pixel }.
// Version 1 ("MSBLOG1\n", payloads back to back without length or checksum) is still read.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/common/messages.h"

namespace msb {

/// The first bytes of every perception log (any version): what --record --overwrite may replace.
inline constexpr char kPerceptionLogMagic[] = "MSBLOG";

/// One recorded frame.
struct LoggedFrame {
  SlamPointsFrame points;  ///< estimate pose + SLAM points
  Pose T_W_C_truth = Pose::Identity();
};

/// Appends frames to a log file (written to "<path>.tmp", renamed by close()).
class PerceptionLogWriter {
 public:
  /// Opens the file and writes the header. Throws std::runtime_error.
  PerceptionLogWriter(const std::string& path, const nlohmann::json& header);
  ~PerceptionLogWriter();
  /// Appends a frame.
  void write(const SlamPointsFrame& frame, const Pose& T_W_C_truth);
  /// Finishes the file (rename into place).
  void close();

 private:
  std::string path_;
  std::FILE* f_ = nullptr;
};

/// Reads a whole log. Throws std::runtime_error naming the file on a bad or truncated log.
struct PerceptionLog {
  nlohmann::json header;
  std::vector<LoggedFrame> frames;
  static PerceptionLog read(const std::string& path);
};

}  // namespace msb
