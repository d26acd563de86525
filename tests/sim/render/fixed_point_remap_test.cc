#include "sim/render/fixed_point_remap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <opencv2/imgproc.hpp>

namespace msb {
namespace {

cv::Mat openCvRemap(const cv::Mat& source, const cv::Mat& map_xy, const cv::Mat& map_interp) {
  cv::Mat out;
  cv::remap(source, out, map_xy, map_interp, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
  return out;
}

// Random source pixels and sample positions spread over the source, its border and beyond,
// with every one of the 32 x 32 sub-pixel positions.
TEST(FixedPointRemap, GivesExactlyWhatCvRemapGivesInsideAtTheBorderAndOutside) {
  std::mt19937 rng(7);
  cv::Mat source(61, 83, CV_8UC1);
  cv::randu(source, 0, 256);
  cv::Mat map_x(120, 150, CV_32F), map_y(120, 150, CV_32F);
  std::uniform_real_distribution<float> x_of(-3.0f, 86.0f), y_of(-3.0f, 64.0f);
  for (int v = 0; v < map_x.rows; ++v)
    for (int u = 0; u < map_x.cols; ++u) map_x.at<float>(v, u) = x_of(rng), map_y.at<float>(v, u) = y_of(rng);
  map_x.at<float>(0, 0) = -100.0f, map_y.at<float>(0, 0) = -100.0f;  // far outside, like the lens' rim
  for (int k = 0; k < 32 * 32; ++k)                                  // every sub-pixel position, inside
    map_x.at<float>(10 + k / 150, k % 150) = 20.0f + (k % 32) / 32.0f,
                                      map_y.at<float>(10 + k / 150, k % 150) = 30.0f + (k / 32) / 32.0f;
  cv::Mat map_xy, map_interp;
  cv::convertMaps(map_x, map_y, map_xy, map_interp, CV_16SC2);

  const FixedPointRemap remap(map_xy, map_interp, source.size());
  cv::Mat ours;
  remap.apply(source, ours);
  const cv::Mat expected = openCvRemap(source, map_xy, map_interp);
  ASSERT_EQ(ours.size(), expected.size());
  EXPECT_EQ(cv::countNonZero(ours != expected), 0);
  EXPECT_EQ(ours.at<uint8_t>(0, 0), 0);
  // The table is reused: a second image through the same table.
  cv::randu(source, 0, 256);
  remap.apply(source, ours);
  EXPECT_EQ(cv::countNonZero(ours != openCvRemap(source, map_xy, map_interp)), 0);
}

TEST(FixedPointRemap, RefusesAnImageOfAnotherSize) {
  cv::Mat map_x(4, 4, CV_32F, cv::Scalar(1.0f)), map_y(4, 4, CV_32F, cv::Scalar(1.0f)), map_xy, map_interp;
  cv::convertMaps(map_x, map_y, map_xy, map_interp, CV_16SC2);
  const FixedPointRemap remap(map_xy, map_interp, cv::Size(8, 8));
  cv::Mat out;
  EXPECT_THROW(remap.apply(cv::Mat(9, 8, CV_8UC1, cv::Scalar(0)), out), std::invalid_argument);
}

}  // namespace
}  // namespace msb
