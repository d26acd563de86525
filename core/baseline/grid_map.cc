#include "core/baseline/grid_map.h"

#include <algorithm>
#include <cmath>

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

void GridMapConfig::validate(ConfigChecker& c) const {
  c.inRange("resolution_m", resolution_m, 0.05, 5.0);
  c.positive("max_range_m", max_range_m);
  c.positive("free_ray_length_m", free_ray_length_m);
  c.inRange("prob_hit", prob_hit, 0.5, 1.0);
  c.inRange("prob_miss", prob_miss, 0.0, 0.5);
  c.inRange("clamp_min", clamp_min, 0.0, 0.5);
  c.inRange("clamp_max", clamp_max, 0.5, 1.0);
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
  pts.reserve(frame.points.size());
  for (const auto& p : frame.points) pts.push_back(p.p_W);
  return insertScan(frame.T_W_C.translation(), pts);
}

GridUpdateStats GridMap::insertScan(const Vec3& origin, const std::vector<Vec3>& points) {
  GridUpdateStats st;
  std::vector<uint64_t> free_keys, occupied_keys;
  octomap::KeyRay ray;
  const octomap::point3d o = toPoint(origin);
  for (const Vec3& p : points) {
    if (!p.allFinite()) continue;
    ++st.points;
    const double d = (p - origin).norm();
    if (d < 1e-6) continue;
    // Occupied end cell within range; free cells along the ray up to the free-ray length.
    octomap::OcTreeKey end_key;
    if (d <= config_.max_range_m && tree_->coordToKeyChecked(toPoint(p), end_key))
      occupied_keys.push_back(packKey(end_key));
    const double free_len = std::min(d, config_.free_ray_length_m);
    const Vec3 free_end = origin + (free_len / d) * (p - origin);
    if (tree_->computeRayKeys(o, toPoint(free_end), ray))
      for (const auto& k : ray) free_keys.push_back(packKey(k));
    // A ray cut short of its point also clears the cell it ends in.
    if (free_len < d) {
      octomap::OcTreeKey k;
      if (tree_->coordToKeyChecked(toPoint(free_end), k)) free_keys.push_back(packKey(k));
    }
  }
  // Sorted, unique; occupied wins over free within one scan.
  auto tidy = [](std::vector<uint64_t>& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  };
  tidy(free_keys);
  tidy(occupied_keys);
  std::vector<uint64_t> only_free;
  only_free.reserve(free_keys.size());
  std::set_difference(free_keys.begin(), free_keys.end(), occupied_keys.begin(), occupied_keys.end(),
                      std::back_inserter(only_free));
  for (uint64_t k : only_free) tree_->updateNode(unpackKey(k), false, true);
  for (uint64_t k : occupied_keys) tree_->updateNode(unpackKey(k), true, true);
  tree_->updateInnerOccupancy();
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

std::vector<GridLeaf> GridMap::leaves(bool occupied) const {
  std::vector<GridLeaf> out;
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    if (tree_->isNodeOccupied(*it) != occupied) continue;
    out.push_back({toVec(it.getCoordinate()), it.getSize(), (packKey(it.getKey()) << 5) | it.getDepth()});
  }
  return out;
}

}  // namespace msb
