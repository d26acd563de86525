#include "core/perception/feature_tracker.h"

#include <algorithm>
#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

namespace msb {

void FeatureTrackerConfig::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require(klt_window_px % 2 == 1, "klt_window_px", "must be odd");
}

void dropOutsideWindowRange(const std::vector<cv::Point2f>& points, cv::Size window, cv::Size image,
                            std::vector<uchar>& status) {
  // OpenCV's arithmetic: the window corner in float, floored; NaN fails every comparison.
  const float half_w = (window.width - 1) * 0.5f, half_h = (window.height - 1) * 0.5f;
  for (size_t i = 0; i < points.size() && i < status.size(); ++i) {
    if (!status[i]) continue;
    const float x = std::floor(points[i].x - half_w), y = std::floor(points[i].y - half_h);
    const bool inside =
        x >= float(-window.width) && x < float(image.width) && y >= float(-window.height) && y < float(image.height);
    if (!inside) status[i] = 0;
  }
}

std::vector<cv::KeyPoint> fastWhereFree(const cv::Mat& img, cv::Rect roi, const cv::Mat& mask, int threshold) {
  // A corner at p depends on the pixels within 3 of p and on its 8 neighbours' scores (within
  // 4): a window holding every free pixel's 4-neighbourhood, cut to the roi, finds exactly the
  // corners the roi has at free pixels (cv::FAST skips 3 px at every window edge, and the
  // window's edges are the roi's or 4 px from every free pixel). Rows more than 8 apart go into
  // separate windows, which then do not overlap.
  constexpr int kReach = 4;
  std::vector<cv::KeyPoint> out, kps;
  const int x_end = roi.x + roi.width, y_end = roi.y + roi.height;
  int first = -1, last = -1, lo = x_end, hi = -1;
  auto scan = [&] {
    const cv::Rect window =
        cv::Rect(lo - kReach, first - kReach, hi - lo + 1 + 2 * kReach, last - first + 1 + 2 * kReach) & roi;
    cv::FAST(img(window), kps, threshold, true);
    for (cv::KeyPoint& k : kps) {
      k.pt.x += float(window.x), k.pt.y += float(window.y);
      if (mask.at<uint8_t>(int(k.pt.y), int(k.pt.x))) out.push_back(k);
    }
  };
  for (int y = roi.y; y < y_end; ++y) {
    const uint8_t* row = mask.ptr<uint8_t>(y);
    int x0 = roi.x, x1 = x_end - 1;
    while (x0 < x_end && !row[x0]) ++x0;
    if (x0 == x_end) continue;  // no free pixel in this row
    while (!row[x1]) --x1;
    if (first >= 0 && y - last > 2 * kReach) scan(), lo = x_end, hi = -1, first = -1;
    if (first < 0) first = y;
    last = y, lo = std::min(lo, x0), hi = std::max(hi, x1);
  }
  if (first >= 0) scan();
  return out;
}

int trackedFromPrevious(const TrackFrame& f) {
  return int(std::count_if(f.tracks.begin(), f.tracks.end(), [](const Track& t) { return t.age >= 1; }));
}

std::vector<bool> KltFeatureTracker::epipolarInliers(const std::vector<Vec2>& prev_px, const std::vector<Vec2>& new_px,
                                                     TrackFrame& out) const {
  std::vector<bool> keep(prev_px.size(), true);
  if (!config_.ransac) return keep;
  // Bearings; the estimate uses those close enough to the axis for normalised coordinates.
  std::vector<Vec3> b0(prev_px.size()), b1(prev_px.size());
  std::vector<cv::Point2d> n0, n1;
  const double min_cos = std::cos(config_.ransac_max_angle_deg * M_PI / 180.0);
  for (size_t i = 0; i < prev_px.size(); ++i) {
    b0[i] = camera_.unproject(prev_px[i]).normalized();
    b1[i] = camera_.unproject(new_px[i]).normalized();
    if (b0[i].z() >= min_cos && b1[i].z() >= min_cos) {
      n0.emplace_back(b0[i].x() / b0[i].z(), b0[i].y() / b0[i].z());
      n1.emplace_back(b1[i].x() / b1[i].z(), b1[i].y() / b1[i].z());
    }
  }
  if (int(n0.size()) < config_.ransac_min_pairs) return keep;
  // Angular threshold: ransac_threshold_px at the image centre.
  const Vec2 c(0.5 * (camera_.width() - 1), 0.5 * (camera_.height() - 1));
  const double thr = std::acos(std::clamp(
      camera_.unproject(c).normalized().dot(camera_.unproject(c + Vec2(config_.ransac_threshold_px, 0)).normalized()),
      -1.0, 1.0));
  // The fundamental matrix on normalised coordinates, as TrackKLT (7-point RANSAC, LMedS under
  // 15 pairs; OpenCV seeds its generator per call).
  const cv::Mat F = cv::findFundamentalMat(n0, n1, cv::FM_RANSAC, thr, 0.999);
  if (F.rows != 3 || F.cols != 3) return keep;  // degenerate: nothing rejected
  Eigen::Matrix3d Em;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) Em(r, k) = F.at<double>(r, k);
  // Angular epipolar error of every pair: distance of b1 from the epipolar plane F b0 (and
  // symmetrically), as a sine.
  for (size_t i = 0; i < prev_px.size(); ++i) {
    const Vec3 l1 = Em * b0[i], l0 = Em.transpose() * b1[i];
    const double e = std::abs(b1[i].dot(l1));
    const double n = std::max(l1.norm(), l0.norm());
    ++out.ransac_tested;
    if (n > 1e-12 && e / n > thr) {
      keep[i] = false;
      ++out.ransac_rejected;
    }
  }
  return keep;
}

KltFeatureTracker::KltFeatureTracker(const FeatureTrackerConfig& config, const FisheyeCamera& camera)
    : config_(checkValid(config)), camera_(camera) {
  // Valid pixels: inside the FoV cone, eroded by the border margin.
  valid_mask_ = cv::Mat(camera.height(), camera.width(), CV_8UC1, cv::Scalar(0));
  for (int v = 0; v < camera.height(); ++v)
    for (int u = 0; u < camera.width(); ++u)
      if (camera.pixelInFov(Vec2(u, v))) valid_mask_.at<uint8_t>(v, u) = 255;
  if (config_.border_px > 0) {
    cv::Mat padded;
    cv::copyMakeBorder(valid_mask_, padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, 0);
    cv::erode(
        padded, padded,
        cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * config_.border_px + 1, 2 * config_.border_px + 1)));
    valid_mask_ = padded(cv::Rect(1, 1, camera.width(), camera.height())).clone();
  }
}

std::vector<Track> KltFeatureTracker::trackForward(const std::vector<cv::Mat>& pyramid, cv::Size image,
                                                   TrackFrame& out) {
  const cv::Size win(config_.klt_window_px, config_.klt_window_px);
  std::vector<Track> tracks;
  std::vector<cv::Point2f> p0, p1, p0_back;
  for (const auto& t : prev_tracks_) p0.emplace_back(float(t.pixel.x()), float(t.pixel.y()));
  std::vector<uchar> st_f, st_b;
  const cv::TermCriteria crit(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, config_.klt_max_iterations, 0.01);
  // No error output: the tracker never reads it, and OpenCV would spend one more window pass
  // per point on it. Its one side effect on the status is reproduced below.
  cv::calcOpticalFlowPyrLK(prev_pyramid_, pyramid, p0, p1, st_f, cv::noArray(), win, config_.klt_pyramid_levels, crit);
  dropOutsideWindowRange(p1, win, image, st_f);
  // Backward pass only for the points the forward pass tracked: LK solves every point on its
  // own, so this gives the same results for them and skips the lost ones.
  std::vector<size_t> forward_ok;
  std::vector<cv::Point2f> p1_ok;
  for (size_t i = 0; i < p0.size(); ++i)
    if (st_f[i]) forward_ok.push_back(i), p1_ok.push_back(p1[i]);
  std::vector<uchar> st_b_ok;
  std::vector<cv::Point2f> p0_back_ok;
  if (!config_.forward_backward_check) {
    // Forward only: every forward-tracked point counts as consistent with itself.
    p0_back_ok.reserve(forward_ok.size());
    for (size_t k : forward_ok) p0_back_ok.push_back(p0[k]);
    st_b_ok.assign(forward_ok.size(), 1);
  } else if (!p1_ok.empty()) {
    cv::calcOpticalFlowPyrLK(pyramid, prev_pyramid_, p1_ok, p0_back_ok, st_b_ok, cv::noArray(), win,
                             config_.klt_pyramid_levels, crit);
    dropOutsideWindowRange(p0_back_ok, win, image, st_b_ok);
  }
  st_b.assign(p0.size(), 0);
  p0_back.assign(p0.size(), cv::Point2f());
  for (size_t k = 0; k < forward_ok.size(); ++k)
    st_b[forward_ok[k]] = st_b_ok[k], p0_back[forward_ok[k]] = p0_back_ok[k];
  std::vector<Vec2> from, to;
  for (size_t i = 0; i < p0.size(); ++i) {
    if (!st_f[i] || !st_b[i]) continue;
    const double fb = std::hypot(p0[i].x - p0_back[i].x, p0[i].y - p0_back[i].y);
    // A mis-track (degradation, off by default) lands the track a few pixels off.
    const Vec2 pixel = Vec2(p1[i].x, p1[i].y) + (mistracks_ ? mistracks_->displacement() : Vec2::Zero());
    const int u = int(std::lround(pixel.x())), v = int(std::lround(pixel.y()));
    if (fb > config_.fb_max_error_px || u < 0 || v < 0 || u >= image.width || v >= image.height ||
        !valid_mask_.at<uint8_t>(v, u))
      continue;
    Track t = prev_tracks_[i];
    from.push_back(t.pixel);
    t.pixel = pixel;
    to.push_back(t.pixel);
    ++t.age;
    tracks.push_back(t);
  }
  // Epipolar outliers (RANSAC) leave.
  const std::vector<bool> inlier = epipolarInliers(from, to, out);
  std::vector<Track> consistent;
  for (size_t i = 0; i < tracks.size(); ++i)
    if (inlier[i]) consistent.push_back(tracks[i]);
  tracks = std::move(consistent);
  return tracks;
}

TrackFrame KltFeatureTracker::process(const CameraFrame& frame) {
  TrackFrame out;
  out.tick = frame.tick;
  out.t_s = frame.t_s;
  cv::Mat img(frame.height, frame.width, CV_8UC1, const_cast<uint8_t*>(frame.pixels.data()));
  // Into buffers kept from frame to frame (OpenCV reuses a buffer of the right size).
  if (config_.equalize_histogram) {
    cv::equalizeHist(img, image_);
  } else {
    img.copyTo(image_);
  }
  img = image_;
  std::vector<cv::Mat>& pyramid = spare_pyramid_;
  const cv::Size win(config_.klt_window_px, config_.klt_window_px);
  cv::buildOpticalFlowPyramid(img, pyramid, win, config_.klt_pyramid_levels);

  // Track the previous features forward (as OpenVINS' TrackKLT), with the optional backward
  // check; keep the ones inside the valid mask; drop epipolar outliers.
  std::vector<Track> tracks;
  if (!prev_tracks_.empty() && !prev_pyramid_.empty()) tracks = trackForward(pyramid, img.size(), out);
  // Tracks that converged onto each other: keep the older (lower id) one.
  std::vector<Track> kept;
  for (const auto& t : tracks) {
    bool clash = false;
    for (const auto& k : kept) clash = clash || (k.pixel - t.pixel).norm() < 0.5 * config_.min_distance_px;
    if (!clash) kept.push_back(t);
  }
  out.lost_tracks = int(prev_tracks_.size() - kept.size());

  detect(img, kept, &out.new_tracks);
  std::sort(kept.begin(), kept.end(), [](const Track& a, const Track& b) { return a.id < b.id; });
  out.tracks = kept;
  prev_tracks_ = kept;
  std::swap(prev_pyramid_, spare_pyramid_);  // this frame's pyramid is the next one's previous
  return out;
}

void KltFeatureTracker::detect(const cv::Mat& img, std::vector<Track>& tracks, int* added) {
  *added = 0;
  const int free_slots = config_.max_tracks - int(tracks.size());
  if (free_slots <= 0) return;
  // Mask: valid pixels not within min_distance of an existing track.
  cv::Mat mask = valid_mask_.clone();
  const int r = int(std::ceil(config_.min_distance_px));
  for (const auto& t : tracks) cv::circle(mask, cv::Point(int(t.pixel.x()), int(t.pixel.y())), r, 0, -1);

  // FAST per grid cell, strongest first; each cell may fill up to its share of max_tracks.
  const int cells = config_.grid_cols * config_.grid_rows;
  const int per_cell = std::max(1, config_.max_tracks / cells);
  std::vector<int> cell_count(cells, 0);
  for (const auto& t : tracks) {
    const int cx = std::min(config_.grid_cols - 1, int(t.pixel.x() * config_.grid_cols / img.cols));
    const int cy = std::min(config_.grid_rows - 1, int(t.pixel.y() * config_.grid_rows / img.rows));
    ++cell_count[cy * config_.grid_cols + cx];
  }
  struct Candidate {
    cv::KeyPoint kp;
    int cell;
  };
  std::vector<Candidate> candidates;
  // A cell already full stays full (counts only grow below), so its corners could never be
  // taken: it is not searched.
  for (int cy = 0; cy < config_.grid_rows; ++cy)
    for (int cx = 0; cx < config_.grid_cols; ++cx) {
      if (cell_count[cy * config_.grid_cols + cx] >= per_cell) continue;
      const int x0 = cx * img.cols / config_.grid_cols, x1 = (cx + 1) * img.cols / config_.grid_cols;
      const int y0 = cy * img.rows / config_.grid_rows, y1 = (cy + 1) * img.rows / config_.grid_rows;
      const cv::Rect roi(x0, y0, x1 - x0, y1 - y0);
      for (const cv::KeyPoint& k : fastWhereFree(img, roi, mask, config_.fast_threshold))
        candidates.push_back({k, cy * config_.grid_cols + cx});
    }
  // Deterministic order: response, then position.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.kp.response != b.kp.response) return a.kp.response > b.kp.response;
    if (a.kp.pt.y != b.kp.pt.y) return a.kp.pt.y < b.kp.pt.y;
    return a.kp.pt.x < b.kp.pt.x;
  });
  for (const auto& c : candidates) {
    if (*added >= free_slots) break;
    if (cell_count[c.cell] >= per_cell) continue;
    const int u = int(c.kp.pt.x), v = int(c.kp.pt.y);
    if (!mask.at<uint8_t>(v, u)) continue;  // taken by a feature added just before
    tracks.push_back({next_id_++, Vec2(c.kp.pt.x, c.kp.pt.y), 0});
    ++cell_count[c.cell];
    ++*added;
    cv::circle(mask, cv::Point(u, v), r, 0, -1);
  }
}

}  // namespace msb
