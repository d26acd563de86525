#include "tools/results/perception_log.h"

#include "core/common/rng.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <set>
#include <stdexcept>

#include "core/common/config_check.h"

namespace msb {

namespace {

constexpr char kMagicV1[] = "MSBLOG1\n";  // frames back to back (read, no longer written)
constexpr char kMagic[] = "MSBLOG2\n";    // frames with a length and a checksum
constexpr uint32_t kMaxFrameBytes = 64u << 20;

// Appends the raw bytes of a value to a frame buffer.
template <class T>
void put(std::string& b, const T& v) {
  b.append(reinterpret_cast<const char*>(&v), sizeof(T));
}
void putPose(std::string& b, const Pose& T) {
  const Quat q(T.linear());
  const double v[7] = {T.translation().x(), T.translation().y(), T.translation().z(), q.w(), q.x(), q.y(), q.z()};
  b.append(reinterpret_cast<const char*>(v), sizeof(v));
}

// Bounded, validating reader of a log file: every value must be finite and within ±1e6; a
// short read names the frame it happened in.
class Reader {
 public:
  Reader(const std::string& path, std::FILE* f) : path_(path), f_(f) {}
  void setFrame(long frame) { frame_ = frame; }
  // Reads from `buffer` instead of the file until clearBuffer() (a checked v2 frame).
  void useBuffer(std::string buffer) { buf_ = std::move(buffer), pos_ = 0, buffered_ = true; }
  void clearBuffer() {
    if (pos_ != buf_.size()) fail("frame length does not match its content");
    buffered_ = false;
  }
  template <class T>
  T get() {
    T v;
    if (buffered_) {
      if (pos_ + sizeof(T) > buf_.size()) fail("frame shorter than its content");
      std::memcpy(&v, buf_.data() + pos_, sizeof(T));
      pos_ += sizeof(T);
    } else if (std::fread(&v, sizeof(T), 1, f_) != 1) {
      fail("truncated");
    }
    return v;
  }
  std::string bytes(size_t n) {
    std::string b(n, '\0');
    if (n && std::fread(b.data(), 1, n, f_) != n) fail("truncated");
    return b;
  }
  double real() {
    const double v = get<double>();
    if (!std::isfinite(v) || std::abs(v) > 1e6) fail("value out of range (" + std::to_string(v) + ")");
    return v;
  }
  Pose pose() {
    double v[7];
    for (double& x : v) x = real();
    const Quat q(v[3], v[4], v[5], v[6]);
    if (q.norm() < 1e-6) fail("degenerate orientation");
    // The writer stores unit quaternions (to 1e-15): anything else was not written by msbench.
    if (std::abs(q.norm() - 1.0) > 1e-6)
      fail("orientation quaternion not normalised (|q| = " + std::to_string(q.norm()) + ")");
    Pose T = Pose::Identity();
    T.translation() = Vec3(v[0], v[1], v[2]);
    T.linear() = q.normalized().toRotationMatrix();
    return T;
  }
  // A text line of at most `max_len` characters.
  std::string line(size_t max_len) {
    std::string s;
    for (int c; (c = std::fgetc(f_)) != '\n';) {
      if (c == EOF) fail("truncated header");
      if (s.size() >= max_len) fail("header line too long");
      s.push_back(char(c));
    }
    return s;
  }
  bool done() {
    const int c = std::fgetc(f_);
    if (c == EOF) return true;
    std::ungetc(c, f_);
    return false;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw FileConfigError(path_ + ": " + what + (frame_ >= 0 ? " in frame " + std::to_string(frame_) : "") +
                          " (a corrupt or truncated perception log)");
  }

 private:
  std::string path_;
  std::FILE* f_;
  long frame_ = -1;
  std::string buf_;
  size_t pos_ = 0;
  bool buffered_ = false;
};

// The header's known keys have the types the writer gives them.
void checkHeader(const std::string& path, const nlohmann::json& h) {
  auto bad = [&](const char* key, const char* want) {
    throw FileConfigError(path + ": log header key '" + key + "': expected " + want + ", got " + h[key].dump());
  };
  for (const char* key : {"world", "scenario"})
    if (h.contains(key) && !h[key].is_string()) bad(key, "a string");
  if (h.contains("world") && h["world"].get<std::string>().empty()) bad("world", "a world name");
  if (h.contains("seed") && !h["seed"].is_number_unsigned()) bad("seed", "a non-negative integer");
  if (h.contains("camera_scale") && !h["camera_scale"].is_number()) bad("camera_scale", "a number");
}

// A frame's contents are what the front end can produce: time runs forward, every point has a
// positive depth, a non-negative depth uncertainty and an anchor frame that is not in the
// future, and a track appears once per frame.
void checkFrame(const Reader& r, const LoggedFrame& fr, const LoggedFrame* previous) {
  const SlamPointsFrame& f = fr.points;
  if (f.tick < 0) r.fail("negative tick " + std::to_string(f.tick));
  if (previous && (f.tick <= previous->points.tick || f.t_s < previous->points.t_s))
    r.fail("time goes backwards (tick " + std::to_string(f.tick) + ", t = " + std::to_string(f.t_s) + " s after tick " +
           std::to_string(previous->points.tick) + ", t = " + std::to_string(previous->points.t_s) + " s)");
  std::set<uint64_t> ids;
  for (size_t i = 0; i < f.points.size(); ++i) {
    const SlamPoint& p = f.points[i];
    const std::string which = "point " + std::to_string(i) + " (track " + std::to_string(p.track_id) + ")";
    if (!(p.depth_m > 0)) r.fail(which + ": depth " + std::to_string(p.depth_m) + " m is not positive");
    if (!(p.depth_std_m >= 0))
      r.fail(which + ": depth uncertainty " + std::to_string(p.depth_std_m) + " m is negative");
    if (p.anchor_tick < 0 || p.anchor_tick > f.tick)
      r.fail(which + ": anchor tick " + std::to_string(p.anchor_tick) + " is not in [0, the frame's tick " +
             std::to_string(f.tick) + "]");
    if (!ids.insert(p.track_id).second) r.fail(which + ": the track appears twice");
  }
}

}  // namespace

PerceptionLogWriter::PerceptionLogWriter(const std::string& path, const nlohmann::json& header) : path_(path) {
  f_ = std::fopen((path + ".tmp").c_str(), "wb");
  if (!f_) throw std::runtime_error(path + ": cannot write the perception log");
  std::fputs(kMagic, f_);
  std::fputs((header.dump() + "\n").c_str(), f_);
}

PerceptionLogWriter::~PerceptionLogWriter() {
  if (f_) {  // not closed: leave no half-written log behind
    std::fclose(f_);
    std::remove((path_ + ".tmp").c_str());
  }
}

void PerceptionLogWriter::write(const SlamPointsFrame& frame, const Pose& T_W_C_truth) {
  // The frame's payload, then: u32 length, payload, u64 FNV-1a checksum of the payload.
  std::string b;
  put(b, frame.tick);
  put(b, frame.t_s);
  putPose(b, frame.T_W_C);
  putPose(b, T_W_C_truth);
  put(b, uint32_t(frame.points.size()));
  for (const auto& p : frame.points) {
    const double v[14] = {p.p_W.x(),          p.p_W.y(),         p.p_W.z(),     p.cov_W(0, 0),
                          p.cov_W(0, 1),      p.cov_W(0, 2),     p.cov_W(1, 1), p.cov_W(1, 2),
                          p.cov_W(2, 2),      p.depth_m,         p.depth_std_m, double(p.anchor_tick),
                          p.anchor_pixel.x(), p.anchor_pixel.y()};
    put(b, p.track_id);
    b.append(reinterpret_cast<const char*>(v), 11 * sizeof(double));
    put(b, p.anchor_tick);
    b.append(reinterpret_cast<const char*>(v + 12), 2 * sizeof(double));
  }
  const uint32_t n = uint32_t(b.size());
  const uint64_t sum = fnv1a64(b.data(), b.size());
  std::fwrite(&n, sizeof(n), 1, f_);
  std::fwrite(b.data(), 1, b.size(), f_);
  std::fwrite(&sum, sizeof(sum), 1, f_);
}

void PerceptionLogWriter::close() {
  if (!f_) return;
  const bool ok = std::fclose(f_) == 0;
  f_ = nullptr;
  if (!ok) throw std::runtime_error(path_ + ": write failed");
  std::filesystem::rename(path_ + ".tmp", path_);
}

PerceptionLog PerceptionLog::read(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw FileConfigError(path + ": perception log not found");
  if (!std::filesystem::is_regular_file(path, ec))
    throw FileConfigError(path + ": not a regular file (a perception log is a file written by --record)");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw FileConfigError(path + ": cannot open the perception log");
  // The magic bytes first: nothing else is read from a file that is not a log.
  char magic[sizeof(kMagic) - 1];
  if (std::fread(magic, 1, sizeof(magic), f.get()) != sizeof(magic))
    throw FileConfigError(path + ": not an msbench perception log (bad magic)");
  const bool v2 = std::memcmp(magic, kMagic, sizeof(magic)) == 0;
  if (!v2 && std::memcmp(magic, kMagicV1, sizeof(magic)) != 0)
    throw FileConfigError(path + ": not an msbench perception log (bad magic)");
  Reader r(path, f.get());
  PerceptionLog log;
  try {
    // A key twice in one object is refused (the parser would keep the last one silently).
    std::vector<std::set<std::string>> keys;
    const nlohmann::json::parser_callback_t unique = [&](int, nlohmann::json::parse_event_t event,
                                                         nlohmann::json& parsed) {
      if (event == nlohmann::json::parse_event_t::object_start)
        keys.emplace_back();
      else if (event == nlohmann::json::parse_event_t::object_end && !keys.empty())
        keys.pop_back();
      else if (event == nlohmann::json::parse_event_t::key && !keys.empty() &&
               !keys.back().insert(parsed.get<std::string>()).second)
        throw FileConfigError(path + ": bad log header: key '" + parsed.get<std::string>() + "' appears twice");
      return true;
    };
    log.header = nlohmann::json::parse(r.line(1 << 20), unique);
  } catch (const nlohmann::json::exception& e) {
    throw FileConfigError(path + ": bad log header: " + e.what());
  }
  if (!log.header.is_object()) throw FileConfigError(path + ": bad log header: expected a JSON object");
  checkHeader(path, log.header);
  for (long frame = 0; !r.done(); ++frame) {
    r.setFrame(frame);
    if (v2) {  // length, payload, checksum: the payload is checked before it is parsed
      const uint32_t n = r.get<uint32_t>();
      if (n > kMaxFrameBytes) r.fail("implausible frame length " + std::to_string(n));
      std::string payload = r.bytes(n);
      if (r.get<uint64_t>() != fnv1a64(payload.data(), payload.size())) r.fail("checksum mismatch");
      r.useBuffer(std::move(payload));
    }
    LoggedFrame fr;
    fr.points.tick = r.get<int64_t>();
    fr.points.t_s = r.real();
    fr.points.T_W_C = r.pose();
    fr.T_W_C_truth = r.pose();
    const uint32_t count = r.get<uint32_t>();
    if (count > 100000) r.fail("implausible point count " + std::to_string(count));
    for (uint32_t i = 0; i < count; ++i) {
      SlamPoint p;
      p.track_id = r.get<uint64_t>();
      double v[11];
      for (double& x : v) x = r.real();
      p.p_W = Vec3(v[0], v[1], v[2]);
      p.cov_W << v[3], v[4], v[5], v[4], v[6], v[7], v[5], v[7], v[8];
      p.depth_m = v[9];
      p.depth_std_m = v[10];
      p.anchor_tick = r.get<int64_t>();
      const double u = r.real(), w = r.real();
      p.anchor_pixel = Vec2(u, w);
      fr.points.points.push_back(p);
    }
    if (v2) r.clearBuffer();
    checkFrame(r, fr, log.frames.empty() ? nullptr : &log.frames.back());
    log.frames.push_back(std::move(fr));
  }
  return log;
}

}  // namespace msb
