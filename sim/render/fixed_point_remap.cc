#include "sim/render/fixed_point_remap.h"

#include <stdexcept>

namespace msb {

namespace {
constexpr int kTabBits = 5;  // cv::INTER_BITS: 32 sub-pixel positions per axis
constexpr int kTab = 1 << kTabBits;
}  // namespace

FixedPointRemap::FixedPointRemap(const cv::Mat& map_xy, const cv::Mat& map_interp, cv::Size source_size)
    : source_size_(source_size), out_size_(map_xy.size()) {
  if (map_xy.type() != CV_16SC2 || map_interp.type() != CV_16UC1 || map_interp.size() != map_xy.size())
    throw std::invalid_argument("FixedPointRemap: expects CV_16SC2 and CV_16UC1 maps of one size");
  const int W = source_size.width, H = source_size.height;
  for (int v = 0; v < out_size_.height; ++v) {
    const cv::Vec2s* xy = map_xy.ptr<cv::Vec2s>(v);
    const uint16_t* interp = map_interp.ptr<uint16_t>(v);
    for (int u = 0; u < out_size_.width; ++u) {
      const int x = xy[u][0], y = xy[u][1];
      const auto fx = uint16_t(interp[u] & (kTab - 1)), fy = uint16_t((interp[u] >> kTabBits) & (kTab - 1));
      const int32_t index = v * out_size_.width + u;
      if (x >= 0 && y >= 0 && x < W - 1 && y < H - 1) {
        const auto a = uint16_t(kTab - fx), c = uint16_t(kTab - fy);
        inner_.push_back({y * W + x, index, {uint16_t(a * c), uint16_t(fx * c), uint16_t(a * fy), uint16_t(fx * fy)}});
      } else if (x + 1 >= 0 && y + 1 >= 0 && x < W && y < H) {  // partly inside
        border_.push_back({x, y, index, fx, fy});
      }
      // Otherwise entirely outside: the border value 0.
    }
  }
}

void FixedPointRemap::apply(const cv::Mat& source, cv::Mat& out) const {
  if (source.type() != CV_8UC1 || source.size() != source_size_ || !source.isContinuous())
    throw std::invalid_argument("FixedPointRemap: source must be a continuous CV_8UC1 image of the table's size");
  // Samples entirely outside the source are 0 and never written: zero only a new image.
  if (out.size() != out_size_ || out.type() != CV_8UC1 || !out.isContinuous()) out = cv::Mat::zeros(out_size_, CV_8UC1);
  const uint8_t* s = source.data;
  uint8_t* d = out.data;
  const int W = source_size_.width;
  // OpenCV's bilinear weights for 8-bit images are (32 - f) * f' * 32 in units of 2^-15, so
  // the 2^-15 rounding of their sum equals a 2^-10 rounding of the unscaled products (the
  // products are exact integers: prepared once, the same sum).
  for (const InnerSample& p : inner_) {
    const uint8_t* q = s + p.source_offset;
    const int sum = q[0] * p.w[0] + q[1] * p.w[1] + q[W] * p.w[2] + q[W + 1] * p.w[3];
    d[p.out_index] = uint8_t((sum + (1 << (2 * kTabBits - 1))) >> (2 * kTabBits));
  }
  for (const BorderSample& p : border_) {
    auto at = [&](int x, int y) -> int {
      return x >= 0 && y >= 0 && x < W && y < source_size_.height ? s[y * W + x] : 0;
    };
    const int a = kTab - p.fx, b = p.fx, c = kTab - p.fy, e = p.fy;
    const int sum =
        (at(p.x, p.y) * a + at(p.x + 1, p.y) * b) * c + (at(p.x, p.y + 1) * a + at(p.x + 1, p.y + 1) * b) * e;
    d[p.out_index] = uint8_t((sum + (1 << (2 * kTabBits - 1))) >> (2 * kTabBits));
  }
}

}  // namespace msb
