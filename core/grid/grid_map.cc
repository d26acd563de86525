#include "core/grid/grid_map.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace msb {

namespace {

// Keys as sortable integers (x, y, z in 16 bits each).
uint64_t packKey(const octomap::OcTreeKey& k) {
  return (uint64_t(k[0]) << 32) | (uint64_t(k[1]) << 16) | uint64_t(k[2]);
}
octomap::OcTreeKey unpackKey(uint64_t v) {
  return octomap::OcTreeKey(uint16_t(v >> 32), uint16_t(v >> 16), uint16_t(v));
}
octomap::point3d toPoint(const Vec3& p) { return octomap::point3d(float(p.x()), float(p.y()), float(p.z())); }
Vec3 toVec(const octomap::point3d& p) { return Vec3(p.x(), p.y(), p.z()); }

}  // namespace

void GridMapConfig::validate(ConfigChecker& c) const { checkFields(*this, c); }

double extrinsicQuality(const Vec3& a, const Vec3& b, const Vec3& d) {
  const double na = a.norm(), nb = b.norm(), nd = d.norm();
  if (na < 1e-12 || nb < 1e-12 || nd < 1e-12) return 0.0;                 // no baseline: no depth
  const double h_ab = std::max(a.dot(b) / (na * nb), 0.0);                // Eq. 3-4
  const double s_ad = a.dot(d) / (na * nd), s_bd = b.dot(d) / (nb * nd);  // Eq. 5-6
  const double r_ad = std::sqrt(std::max(0.0, 1 - s_ad * s_ad)),
               r_bd = std::sqrt(std::max(0.0, 1 - s_bd * s_bd));  // 7-8
  return std::min({h_ab, r_ad, r_bd});                            // Eq. 9
}

double confidenceWeight(const SlamPoint& p, const Pose& T_W_C, double depth_gain_per_m) {
  const Vec3 a = p.T_W_anchor.linear().col(2), b = T_W_C.linear().col(2);
  const Vec3 d = T_W_C.translation() - p.T_W_anchor.translation();
  const double depth_confidence = std::max(1.0 - depth_gain_per_m * 2.0 * p.depth_std_m / 100.0, 0.0);  // Eq. 10
  return extrinsicQuality(a, b, d) * depth_confidence;
}

GridMap::GridMap(const GridMapConfig& config)
    : config_(checkValid(config)), tree_(std::make_unique<octomap::OcTree>(config.resolution_m)) {
  tree_->setProbHit(config.prob_hit);
  tree_->setProbMiss(config.prob_miss);
  tree_->setClampingThresMin(config.clamp_min);
  tree_->setClampingThresMax(config.clamp_max);
}

GridUpdateStats GridMap::insert(const SlamPointsFrame& frame) {
  std::vector<Vec3> pts;
  std::vector<double> weights;
  pts.reserve(frame.points.size());
  for (const auto& p : frame.points) {
    pts.push_back(p.p_W);
    if (config_.weighted()) weights.push_back(confidenceWeight(p, frame.T_W_C, config_.confidence_depth_gain_per_m));
  }
  return insertScan(frame.T_W_C.translation(), pts, weights);
}

GridUpdateStats GridMap::insertScan(const Vec3& origin, const std::vector<Vec3>& points,
                                    const std::vector<double>& weights) {
  GridUpdateStats st;
  last_watched_.clear();
  // (key, weight) pairs; with standard insertion every weight is 1.
  std::vector<std::pair<uint64_t, double>> free_keys, occupied_keys;
  octomap::KeyRay ray;
  const octomap::point3d o = toPoint(origin);
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    if (!p.allFinite()) continue;
    const double w = weights.empty() ? 1.0 : weights[i];
    ++st.points;
    st.weight_sum += w;
    const double d = (p - origin).norm();
    if (d < 1e-6 || w <= 0.0) continue;
    // Occupied end cell within range; free cells along the ray up to the free-ray length.
    octomap::OcTreeKey end_key;
    std::optional<uint64_t> hit_key;
    if (d <= config_.max_range_m && tree_->coordToKeyChecked(toPoint(p), end_key)) {
      hit_key = packKey(end_key);
      occupied_keys.push_back({*hit_key, w});
    }
    const double free_len = std::min(d, config_.free_ray_length_m);
    const Vec3 free_end = origin + (free_len / d) * (p - origin);
    if (tree_->computeRayKeys(o, toPoint(free_end), ray))
      for (const auto& k : ray) free_keys.push_back({packKey(k), w});
    // A ray cut short of its point also clears the cell it ends in.
    if (free_len < d) {
      octomap::OcTreeKey k;
      if (tree_->coordToKeyChecked(toPoint(free_end), k)) free_keys.push_back({packKey(k), w}), ray.addKey(k);
    }
    if (!watched_.empty()) noteWatched(ray, i, hit_key);
  }
  // Sorted by key, one entry per key with its largest weight; occupied wins over free within
  // one scan.
  auto tidy = [](std::vector<std::pair<uint64_t, double>>& v) {
    std::sort(v.begin(), v.end(), [](const auto& a, const auto& b) {
      return a.first != b.first ? a.first < b.first : a.second > b.second;
    });
    v.erase(std::unique(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.first == b.first; }), v.end());
  };
  tidy(free_keys);
  tidy(occupied_keys);
  std::vector<std::pair<uint64_t, double>> only_free;
  only_free.reserve(free_keys.size());
  size_t j = 0;
  for (const auto& f : free_keys) {
    while (j < occupied_keys.size() && occupied_keys[j].first < f.first) ++j;
    if (j < occupied_keys.size() && occupied_keys[j].first == f.first) continue;
    only_free.push_back(f);
  }
  // Standard: OctoMap's own hit/miss update; weighted: the log-odds scaled by the weight. Lazy
  // (no pruning) unless the map prunes as it updates.
  const float l_hit = octomap::logodds(config_.prob_hit), l_miss = octomap::logodds(config_.prob_miss);
  const bool lazy = !config_.prune;
  for (const auto& [k, w] : only_free) {
    if (config_.weighted())
      tree_->updateNode(unpackKey(k), float(w) * l_miss, lazy);
    else
      tree_->updateNode(unpackKey(k), false, lazy);
  }
  for (const auto& [k, w] : occupied_keys) {
    if (config_.weighted())
      tree_->updateNode(unpackKey(k), float(w) * l_hit, lazy);
    else
      tree_->updateNode(unpackKey(k), true, lazy);
  }
  tree_->updateInnerOccupancy();
  // Watched misses of cells this scan also hit were not made (occupied wins within a scan).
  std::erase_if(last_watched_, [&](const WatchedUpdate& u) {
    return !u.hit &&
           std::binary_search(occupied_keys.begin(), occupied_keys.end(), std::pair<uint64_t, double>{u.key, 0.0},
                              [](const auto& a, const auto& b) { return a.first < b.first; });
  });
  st.free_cells = int(only_free.size());
  st.occupied_cells = int(occupied_keys.size());
  return st;
}

int GridMap::occupancy(const Vec3& p) const {
  const octomap::OcTreeNode* n = tree_->search(toPoint(p));
  if (!n) return -1;
  return tree_->isNodeOccupied(n) ? 1 : 0;
}

bool GridMap::occupiedWithin(const Vec3& p, double r) const {
  const Vec3 lo = p - Vec3::Constant(r), hi = p + Vec3::Constant(r);
  for (auto it = tree_->begin_leafs_bbx(toPoint(lo), toPoint(hi)), end = tree_->end_leafs_bbx(); it != end; ++it) {
    if (!tree_->isNodeOccupied(*it)) continue;
    // Distance from p to the leaf's box (a pruned leaf covers several cells).
    const Vec3 c = toVec(it.getCoordinate());
    const double half = 0.5 * it.getSize();
    const Vec3 q = ((p - c).cwiseAbs() - Vec3::Constant(half)).cwiseMax(0.0);
    if (q.norm() <= r) return true;
  }
  return false;
}

std::string GridMap::binary() const {
  std::ostringstream out;
  tree_->writeBinaryConst(out);
  return out.str();
}

std::vector<GridLeaf> GridMap::leaves(bool occupied) const {
  std::vector<GridLeaf> out;
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    if (tree_->isNodeOccupied(*it) != occupied) continue;
    out.push_back({toVec(it.getCoordinate()), it.getSize(), (packKey(it.getKey()) << 5) | it.getDepth()});
  }
  return out;
}

void GridMap::watch(std::vector<uint64_t> keys) {
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  watched_ = std::move(keys);
}

void GridMap::noteWatched(const octomap::KeyRay& ray, size_t point, const std::optional<uint64_t>& hit_key) {
  for (const auto& k : ray)
    if (std::binary_search(watched_.begin(), watched_.end(), packKey(k)))
      last_watched_.push_back({packKey(k), int(point), false});
  if (hit_key && std::binary_search(watched_.begin(), watched_.end(), *hit_key))
    last_watched_.push_back({*hit_key, int(point), true});
}

std::optional<uint64_t> GridMap::keyOf(const Vec3& p) const {
  octomap::OcTreeKey k;
  if (!tree_->coordToKeyChecked(toPoint(p), k)) return std::nullopt;
  return packKey(k);
}

Vec3 GridMap::centreOf(uint64_t key) const {
  const octomap::point3d c = tree_->keyToCoord(unpackKey(key));
  return Vec3(c.x(), c.y(), c.z());
}

std::optional<double> GridMap::probabilityOf(uint64_t key) const {
  const octomap::OcTreeNode* n = tree_->search(unpackKey(key));
  if (!n) return std::nullopt;
  return n->getOccupancy();
}

bool pathNearOccupied(const GridMap& map, const std::vector<Vec3>& path, const Vec3& from, double ahead_m,
                      double clearance_m) {
  if (path.size() < 2) return false;
  double s = 0;
  Vec3 a = from;
  for (size_t i = 1; i < path.size() && s < ahead_m; ++i) {
    const Vec3 b = path[i];
    const double len = (b - a).norm();
    for (double t = 0.25; t <= len && s + t <= ahead_m; t += 0.25)
      if (map.occupiedWithin(a + t / len * (b - a), clearance_m)) return true;
    s += len;
    a = b;
  }
  return false;
}

std::vector<FreeSpaceElement> freeLeaves(const GridMap& map) {
  std::vector<FreeSpaceElement> out;
  for (const GridLeaf& leaf : map.leaves(false))
    out.push_back({leaf.id, leaf.centre, 0.5 * leaf.size_m, FreeSpaceElement::Footprint::kSquare});
  return out;
}

ExplorerSnapshot gridSnapshot(const GridMap& map, const std::optional<Vec3>& goal, const std::vector<Vec3>& path) {
  ExplorerSnapshot snap;
  snap.free_space = freeLeaves(map);
  for (const GridLeaf& leaf : map.leaves(true)) snap.obstacles.push_back(leaf.centre);
  if (goal) snap.goal = ExplorerSnapshot::Pose2{*goal, 0.0};
  snap.path = path;
  return snap;
}

std::vector<Waypoint> pathWaypoints(const std::vector<Vec3>& points) {
  std::vector<Waypoint> w;
  for (size_t i = 1; i < points.size(); ++i) w.push_back({points[i], std::nullopt});
  return w;
}

}  // namespace msb
