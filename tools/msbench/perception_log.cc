#include "tools/msbench/perception_log.h"

#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace msb {

namespace {

constexpr char kMagic[] = "MSBLOG1\n";

void putPose(std::FILE* f, const Pose& T) {
  const Quat q(T.linear());
  const double v[7] = {T.translation().x(), T.translation().y(), T.translation().z(), q.w(), q.x(), q.y(), q.z()};
  std::fwrite(v, sizeof(double), 7, f);
}

class Reader {
 public:
  Reader(const std::string& path, std::string bytes) : path_(path), b_(std::move(bytes)) {}
  template <class T>
  T get() {
    if (pos_ + sizeof(T) > b_.size()) throw std::runtime_error(path_ + ": truncated perception log");
    T v;
    std::memcpy(&v, b_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  Pose pose() {
    double v[7];
    for (double& x : v) x = get<double>();
    Pose T = Pose::Identity();
    T.translation() = Vec3(v[0], v[1], v[2]);
    T.linear() = Quat(v[3], v[4], v[5], v[6]).normalized().toRotationMatrix();
    return T;
  }
  std::string line() {
    const auto end = b_.find('\n', pos_);
    if (end == std::string::npos) throw std::runtime_error(path_ + ": truncated perception log");
    std::string s = b_.substr(pos_, end - pos_);
    pos_ = end + 1;
    return s;
  }
  bool done() const { return pos_ >= b_.size(); }

 private:
  std::string path_, b_;
  size_t pos_ = 0;
};

}  // namespace

PerceptionLogWriter::PerceptionLogWriter(const std::string& path, const nlohmann::json& header)
    : path_(path) {
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
  std::fwrite(&frame.tick, sizeof(int64_t), 1, f_);
  std::fwrite(&frame.t_s, sizeof(double), 1, f_);
  putPose(f_, frame.T_W_C);
  putPose(f_, T_W_C_truth);
  const uint32_t n = uint32_t(frame.points.size());
  std::fwrite(&n, sizeof(n), 1, f_);
  for (const auto& p : frame.points) {
    const double v[14] = {p.p_W.x(), p.p_W.y(), p.p_W.z(), p.cov_W(0, 0), p.cov_W(0, 1),
                          p.cov_W(0, 2), p.cov_W(1, 1), p.cov_W(1, 2), p.cov_W(2, 2), p.depth_m,
                          p.depth_std_m, double(p.anchor_tick), p.anchor_pixel.x(), p.anchor_pixel.y()};
    std::fwrite(&p.track_id, sizeof(uint64_t), 1, f_);
    std::fwrite(v, sizeof(double), 11, f_);
    std::fwrite(&p.anchor_tick, sizeof(int64_t), 1, f_);
    std::fwrite(v + 12, sizeof(double), 2, f_);
  }
}

void PerceptionLogWriter::close() {
  if (!f_) return;
  const bool ok = std::fclose(f_) == 0;
  f_ = nullptr;
  if (!ok) throw std::runtime_error(path_ + ": write failed");
  std::filesystem::rename(path_ + ".tmp", path_);
}

PerceptionLog PerceptionLog::read(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error(path + ": cannot open the perception log");
  std::string bytes;
  char buf[1 << 16];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof(buf), f)) > 0) bytes.append(buf, n);
  std::fclose(f);
  if (bytes.compare(0, std::strlen(kMagic), kMagic) != 0)
    throw std::runtime_error(path + ": not an msbench perception log (bad magic)");
  Reader r(path, bytes.substr(std::strlen(kMagic)));
  PerceptionLog log;
  try {
    log.header = nlohmann::json::parse(r.line());
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": bad log header: " + e.what());
  }
  while (!r.done()) {
    LoggedFrame fr;
    fr.points.tick = r.get<int64_t>();
    fr.points.t_s = r.get<double>();
    fr.points.T_W_C = r.pose();
    fr.T_W_C_truth = r.pose();
    const uint32_t count = r.get<uint32_t>();
    for (uint32_t i = 0; i < count; ++i) {
      SlamPoint p;
      p.track_id = r.get<uint64_t>();
      double v[11];
      for (double& x : v) x = r.get<double>();
      p.p_W = Vec3(v[0], v[1], v[2]);
      p.cov_W << v[3], v[4], v[5], v[4], v[6], v[7], v[5], v[7], v[8];
      p.depth_m = v[9];
      p.depth_std_m = v[10];
      p.anchor_tick = r.get<int64_t>();
      const double u = r.get<double>(), w = r.get<double>();
      p.anchor_pixel = Vec2(u, w);
      fr.points.points.push_back(p);
    }
    log.frames.push_back(std::move(fr));
  }
  return log;
}

}  // namespace msb
