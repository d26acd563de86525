#include "core/perception/feature_tracker.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/common/rng.h"

namespace msb {
namespace {

// Smoothed random noise (corners everywhere), shifted by (dx, dy) pixels.
CameraFrame texturedFrame(int w, int h, double dx, double dy, int64_t tick) {
  RngStream rng(5, "tracker_texture");
  cv::Mat noise(h + 200, w + 200, CV_32F);
  for (int v = 0; v < noise.rows; ++v)
    for (int u = 0; u < noise.cols; ++u) noise.at<float>(v, u) = float(rng.uniform(0, 255));
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 2.0);
  cv::Mat big;
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  noise.convertTo(big, CV_8U);
  cv::Mat shifted;
  const cv::Mat M = (cv::Mat_<double>(2, 3) << 1, 0, dx, 0, 1, dy);
  cv::warpAffine(big, shifted, M, big.size(), cv::INTER_LINEAR);
  CameraFrame f;
  f.tick = tick;
  f.width = w;
  f.height = h;
  const cv::Mat roi = shifted(cv::Rect(100, 100, w, h)).clone();
  f.pixels.assign(roi.datastart, roi.dataend);
  return f;
}

TEST(KltFeatureTracker, DetectsUpToTheLimitOnAGridAndFollowsAShift) {
  const FisheyeCamera cam;
  cv::setNumThreads(0);
  KltFeatureTracker tracker(FeatureTrackerConfig{}, cam);
  const TrackFrame a = tracker.process(texturedFrame(cam.width(), cam.height(), 0, 0, 0));
  EXPECT_GT(a.tracks.size(), 250u);
  EXPECT_LE(a.tracks.size(), 400u);
  EXPECT_EQ(a.new_tracks, int(a.tracks.size()));
  // Minimum spacing and FoV.
  for (size_t i = 0; i < a.tracks.size(); ++i) {
    EXPECT_TRUE(cam.pixelInFov(a.tracks[i].pixel));
    for (size_t j = i + 1; j < a.tracks.size(); ++j)
      EXPECT_GE((a.tracks[i].pixel - a.tracks[j].pixel).norm(), 19.0);
  }
  // Shift the image by (3, -2) px: surviving tracks move by that shift, ids and ages kept.
  const TrackFrame b = tracker.process(texturedFrame(cam.width(), cam.height(), 3.0, -2.0, 1));
  int followed = 0;
  for (const auto& t : b.tracks) {
    if (t.age == 0) continue;
    const auto it = std::find_if(a.tracks.begin(), a.tracks.end(), [&](const Track& x) { return x.id == t.id; });
    ASSERT_NE(it, a.tracks.end());
    EXPECT_NEAR(t.pixel.x() - it->pixel.x(), 3.0, 0.25);  // equalisation shifts a little
    EXPECT_NEAR(t.pixel.y() - it->pixel.y(), -2.0, 0.25);
    EXPECT_EQ(t.age, 1);
    ++followed;
  }
  EXPECT_GT(followed, 200);
}

TEST(KltFeatureTracker, BlankImagesGiveNoTracksAndTheSameInputGivesTheSameTracks) {
  const FisheyeCamera cam;
  KltFeatureTracker blank(FeatureTrackerConfig{}, cam);
  CameraFrame f;
  f.width = cam.width();
  f.height = cam.height();
  f.pixels.assign(size_t(f.width) * f.height, 128);
  EXPECT_TRUE(blank.process(f).tracks.empty());
  KltFeatureTracker t1(FeatureTrackerConfig{}, cam), t2(FeatureTrackerConfig{}, cam);
  for (int i = 0; i < 3; ++i) {
    const CameraFrame fr = texturedFrame(cam.width(), cam.height(), 1.3 * i, 0.7 * i, i);
    const TrackFrame a = t1.process(fr), b = t2.process(fr);
    ASSERT_EQ(a.tracks.size(), b.tracks.size());
    for (size_t k = 0; k < a.tracks.size(); ++k) {
      EXPECT_EQ(a.tracks[k].id, b.tracks[k].id);
      EXPECT_EQ(a.tracks[k].pixel, b.tracks[k].pixel);
    }
  }
}

}  // namespace
}  // namespace msb
