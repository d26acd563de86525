#pragma once
// Bilinear remap of a grey image through a fixed lookup table, pixel for pixel the same as
// cv::remap(INTER_LINEAR, BORDER_CONSTANT 0) with a CV_16SC2 + CV_16UC1 map, but with the
// table's addresses and weights prepared once: the fisheye renderer applies the same table to
// every frame, and a third of the fisheye image lies outside the lens' field of view.

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace msb {

/// A remap table prepared for repeated use on 8-bit single-channel images of one size.
class FixedPointRemap {
 public:
  FixedPointRemap() = default;
  /// Prepares the table from cv::convertMaps output (CV_16SC2 integer coordinates and CV_16UC1
  /// interpolation indices, INTER_TAB_SIZE 32) for source images of `source_size`.
  FixedPointRemap(const cv::Mat& map_xy, const cv::Mat& map_interp, cv::Size source_size);

  /// Remaps `source` (CV_8UC1, the size given at construction) into `out` (CV_8UC1, the map's
  /// size); what cv::remap gives with INTER_LINEAR and a constant border of 0. An `out` of the
  /// right size is reused as it is: its pixels outside the source must still be 0 (as left by
  /// an earlier call).
  void apply(const cv::Mat& source, cv::Mat& out) const;

 private:
  // A sample whose four neighbours lie inside the source: its top-left neighbour's offset
  // (row-major, in source pixels), output index and the bilinear weights of its four
  // neighbours (top-left, top-right, bottom-left, bottom-right) in units of 2^-10.
  struct InnerSample {
    int32_t source_offset;
    int32_t out_index;
    uint16_t w[4];
  };
  // A sample at the border (some neighbours outside): its integer position kept as such.
  struct BorderSample {
    int32_t x, y;
    int32_t out_index;
    uint16_t fx, fy;
  };
  cv::Size source_size_, out_size_;
  std::vector<InnerSample> inner_;
  std::vector<BorderSample> border_;
};

}  // namespace msb
