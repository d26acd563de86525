#include "sim/world/procedural_textures.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "core/common/rng.h"

namespace msb {

namespace {

struct Pattern {
  const char* name;
  double tile_m;
};

constexpr Pattern kPatterns[] = {
    {"grass", 2.0},
    {"bricks", 2.0},
    {"facade", 3.0},
    {"concrete", 2.0},
    {"rock", 3.0},
    {"bark", 1.0},
    {"foliage", 2.0},
    {"wood", 1.5},
    {"gravel", 1.5},
    // The collapsed house's burned brick at the reference texture's scale on its model (0.0154 m a
    // texel, 512 texels; docs/worlds.md, "Burned parts").
    {"burned", 7.9},
};

// Periodic value noise: a lattice of `period` × `period` random values, smoothly interpolated.
class PeriodicNoise {
 public:
  PeriodicNoise(int period, RngStream& rng) : period_(period), values_(size_t(period) * period) {
    for (auto& v : values_) v = rng.uniform();
  }
  // u, v in [0, 1): position in the tile.
  double at(double u, double v) const {
    const double x = u * period_, y = v * period_;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double fx = smooth(x - x0), fy = smooth(y - y0);
    auto L = [&](int i, int j) {
      i = ((i % period_) + period_) % period_;
      j = ((j % period_) + period_) % period_;
      return values_[size_t(j) * period_ + i];
    };
    const double a = L(x0, y0) + fx * (L(x0 + 1, y0) - L(x0, y0));
    const double b = L(x0, y0 + 1) + fx * (L(x0 + 1, y0 + 1) - L(x0, y0 + 1));
    return a + fy * (b - a);
  }

 private:
  static double smooth(double t) { return t * t * (3.0 - 2.0 * t); }
  int period_;
  std::vector<double> values_;
};

// Fractal sum of periodic noise octaves (base period doubles per octave), in [0, 1].
cv::Mat fbm(int size, int base_period, int octaves, double persistence, RngStream& rng) {
  std::vector<PeriodicNoise> layers;
  for (int o = 0; o < octaves; ++o) layers.emplace_back(base_period << o, rng);
  cv::Mat out(size, size, CV_64F);
  double norm = 0, amp = 1;
  for (int o = 0; o < octaves; ++o) norm += amp, amp *= persistence;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      double s = 0;
      amp = 1;
      for (const auto& l : layers) s += amp * l.at(double(x) / size, double(y) / size), amp *= persistence;
      out.at<double>(y, x) = s / norm;
    }
  return out;
}

cv::Mat toGrey(const cv::Mat& f, double lo, double hi) {
  cv::Mat out(f.size(), CV_8UC1);
  for (int y = 0; y < f.rows; ++y)
    for (int x = 0; x < f.cols; ++x)
      out.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(lo + (hi - lo) * std::clamp(f.at<double>(y, x), 0.0, 1.0));
  return out;
}

// Filled rectangle with wrap-around (keeps the texture tileable).
void wrapRect(cv::Mat& img, int x0, int y0, int w, int h, int value) {
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x)
      img.at<uint8_t>(((y % img.rows) + img.rows) % img.rows, ((x % img.cols) + img.cols) % img.cols) =
          static_cast<uint8_t>(std::clamp(value, 0, 255));
}

// Filled disc with wrap-around.
void wrapDisc(cv::Mat& img, double cx, double cy, double r, int value) {
  for (int y = int(cy - r); y <= int(cy + r); ++y)
    for (int x = int(cx - r); x <= int(cx + r); ++x)
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r)
        img.at<uint8_t>(((y % img.rows) + img.rows) % img.rows, ((x % img.cols) + img.cols) % img.cols) =
            static_cast<uint8_t>(value);
}

// Adds fine noise (amplitude in grey levels) to break up flat areas.
void addGrain(cv::Mat& img, double amplitude, RngStream& rng) {
  const cv::Mat n = fbm(img.rows, 64, 2, 0.5, rng);
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x)
      img.at<uint8_t>(y, x) =
          cv::saturate_cast<uint8_t>(img.at<uint8_t>(y, x) + amplitude * (n.at<double>(y, x) - 0.5));
}

cv::Mat bricks(int s, RngStream& rng) {
  cv::Mat img(s, s, CV_8UC1, cv::Scalar(185));  // mortar
  const int rows = 16, row_h = s / rows, brick_w = s / 6, mortar = std::max(2, s / 170);
  for (int r = 0; r < rows; ++r) {
    const int offset = (r % 2) * brick_w / 2;
    for (int b = 0; b < 6; ++b)
      wrapRect(img, b * brick_w + offset + mortar, r * row_h + mortar, brick_w - mortar, row_h - mortar,
               int(rng.uniform(55, 150)));
  }
  addGrain(img, 40, rng);
  return img;
}

cv::Mat facade(int s, RngStream& rng) {
  cv::Mat img = toGrey(fbm(s, 8, 4, 0.55, rng), 120, 200);
  // One window per tile (3 m): frame, dark glass with two panes.
  const int w = int(s * 0.4), h = int(s * 0.47), x0 = (s - w) / 2, y0 = int(s * 0.22);
  const int frame = std::max(3, s / 60);
  wrapRect(img, x0 - frame, y0 - frame, w + 2 * frame, h + 2 * frame, 230);
  wrapRect(img, x0, y0, w, h, int(rng.uniform(25, 60)));
  wrapRect(img, x0 + w / 2 - frame / 2, y0, frame, h, 230);
  wrapRect(img, x0 - 2 * frame, y0 + h + frame, w + 4 * frame, 2 * frame, 90);  // sill shadow
  addGrain(img, 25, rng);
  return img;
}

cv::Mat foliage(int s, RngStream& rng) {
  cv::Mat img = toGrey(fbm(s, 4, 3, 0.5, rng), 20, 70);
  const int leaves = s * s / 60;
  for (int i = 0; i < leaves; ++i)
    wrapDisc(img, rng.uniform(0, s), rng.uniform(0, s), rng.uniform(2.0, 6.0) * s / 512.0 + 1.0,
             int(rng.uniform(40, 190)));
  return img;
}

cv::Mat bark(int s, RngStream& rng) {
  // Vertical furrows: noise stretched along v, plus dark cracks.
  std::vector<PeriodicNoise> n;
  for (int p : {8, 16, 32}) n.emplace_back(p, rng);
  cv::Mat img(s, s, CV_8UC1);
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x) {
      const double u = double(x) / s, v = double(y) / s;
      const double a = 0.5 * n[0].at(u, v / 8) + 0.3 * n[1].at(u, v / 4) + 0.2 * n[2].at(u, v);
      const double ridge = std::abs(a - 0.5) * 2;
      img.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(40 + 170 * ridge);
    }
  addGrain(img, 35, rng);
  return img;
}

cv::Mat rock(int s, RngStream& rng) {
  cv::Mat base = fbm(s, 4, 6, 0.6, rng);
  cv::Mat ridged = fbm(s, 8, 4, 0.5, rng);
  cv::Mat img(s, s, CV_8UC1);
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x) {
      const double crack = std::abs(ridged.at<double>(y, x) - 0.5) < 0.02 ? -0.45 : 0.0;
      img.at<uint8_t>(y, x) =
          cv::saturate_cast<uint8_t>(255 * std::clamp(0.15 + 1.1 * (base.at<double>(y, x) - 0.25) + crack, 0.0, 1.0));
    }
  addGrain(img, 30, rng);
  return img;
}

cv::Mat grass(int s, RngStream& rng) {
  cv::Mat img = toGrey(fbm(s, 4, 5, 0.65, rng), 50, 170);
  const int blades = s * s / 80;
  for (int i = 0; i < blades; ++i) {
    const double x = rng.uniform(0, s), y = rng.uniform(0, s), len = rng.uniform(3, 9) * s / 512.0;
    const int value = int(rng.uniform(20, 230));
    for (int k = 0; k < int(len) + 1; ++k) wrapDisc(img, x + 0.3 * k, y - k, 0.8, value);
  }
  return img;
}

cv::Mat concrete(int s, RngStream& rng) {
  cv::Mat img = toGrey(fbm(s, 4, 5, 0.6, rng), 90, 200);
  for (int i = 0; i < s / 3; ++i)  // speckles and chips
    wrapDisc(img, rng.uniform(0, s), rng.uniform(0, s), rng.uniform(1.0, 4.0) * s / 512.0 + 0.5,
             int(rng.uniform(30, 240)));
  return img;
}

cv::Mat wood(int s, RngStream& rng) {
  cv::Mat img(s, s, CV_8UC1);
  const PeriodicNoise grain(16, rng);
  const int planks = 6, plank_h = s / planks;
  std::vector<int> shade(planks);
  for (auto& v : shade) v = int(rng.uniform(70, 170));
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x) {
      const int p = y / plank_h;
      const double g = grain.at(double(x) / s / 4, double(y) / s * 4);
      const bool gap = y % plank_h < std::max(2, s / 200);
      img.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(gap ? 20 : shade[p] + 70 * (g - 0.5));
    }
  addGrain(img, 25, rng);
  return img;
}

cv::Mat gravel(int s, RngStream& rng) {
  cv::Mat img = toGrey(fbm(s, 8, 3, 0.5, rng), 70, 130);
  for (int i = 0; i < s * s / 90; ++i)
    wrapDisc(img, rng.uniform(0, s), rng.uniform(0, s), rng.uniform(1.5, 5.0) * s / 512.0 + 0.5,
             int(rng.uniform(30, 230)));
  return img;
}

// Burned brick under soot, matched to the dark half of the reference's collapsed-house texture
// (docs/worlds.md, "Burned parts"): courses of dark, fire-blackened bricks, and soot that buries
// them in patches (a low-frequency field), leaving near-black, faintly grained areas.
cv::Mat burned(int s, RngStream& rng) {
  const int rows = 120, per_row = 40;
  const double row_h = double(s) / rows, brick_w = double(s) / per_row;
  const int mortar = std::max(1, s / 512);
  cv::Mat img(s, s, CV_8UC1, cv::Scalar(24));  // mortar, darkened
  for (int r = 0; r < rows; ++r) {
    const double offset = (r % 2) * brick_w / 2;
    for (int b = 0; b < per_row; ++b)
      wrapRect(img, int(b * brick_w + offset) + mortar, int(r * row_h) + mortar, int(brick_w) - mortar,
               int(row_h) - mortar, int(rng.uniform(30, 125)));
  }
  addGrain(img, 30, rng);
  // Soot: where the low-frequency field is high, the bricks fade into a dark, faintly grained coat.
  const cv::Mat soot = fbm(s, 3, 4, 0.5, rng), grain = fbm(s, 256, 2, 0.6, rng);
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x) {
      const double w = std::clamp((soot.at<double>(y, x) - 0.42) / 0.16, 0.0, 1.0);
      const double coat = 24 + 24 * (grain.at<double>(y, x) - 0.5);
      uint8_t& v = img.at<uint8_t>(y, x);
      v = cv::saturate_cast<uint8_t>((1 - w) * v + w * coat);
    }
  return img;
}

}  // namespace

const std::vector<std::string>& textureNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& p : kPatterns) n.emplace_back(p.name);
    return n;
  }();
  return names;
}

bool isTextureName(const std::string& name) {
  for (const auto& p : kPatterns)
    if (name == p.name) return true;
  return false;
}

double textureTileMeters(const std::string& name) {
  for (const auto& p : kPatterns)
    if (name == p.name) return p.tile_m;
  throw std::invalid_argument("unknown texture '" + name + "'");
}

cv::Mat makeTexture(const std::string& name, int size_px, uint64_t seed) {
  RngStream rng(seed, "texture_" + name);
  if (name == "grass") return grass(size_px, rng);
  if (name == "bricks") return bricks(size_px, rng);
  if (name == "facade") return facade(size_px, rng);
  if (name == "concrete") return concrete(size_px, rng);
  if (name == "rock") return rock(size_px, rng);
  if (name == "bark") return bark(size_px, rng);
  if (name == "foliage") return foliage(size_px, rng);
  if (name == "wood") return wood(size_px, rng);
  if (name == "gravel") return gravel(size_px, rng);
  if (name == "burned") return burned(size_px, rng);
  throw std::invalid_argument("unknown texture '" + name + "'");
}

}  // namespace msb
