#include "core/grid/grid_path_planner.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <stdexcept>

namespace msb {

void GridPlannerConfig::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require(unknown_clearance_m >= 0.0 || unknown_clearance_m == -1.0, "unknown_clearance_m",
            "must be >= 0 (or -1: the same as clearance_m)");
}

GridPathPlanner::GridPathPlanner(const GridPlannerConfig& config, const Aabb& box, double resolution_m)
    : config_(checkValid(config)), box_(box), res_(resolution_m) {
  if (!(resolution_m > 0) || (box.max.array() <= box.min.array()).any())
    throw ConfigError("exploration_box", "must have a positive size for the grid planner");
  // Cells aligned with the OctoMap grid (boundaries at multiples of the resolution).
  origin_ = (box.min / res_).array().floor().matrix() * res_;
  const Vec3 n = ((box.max - origin_) / res_).array().ceil();
  nx_ = std::max(1, int(n.x()));
  ny_ = std::max(1, int(n.y()));
  nz_ = std::max(1, int(n.z()));
  if (double(nx_) * ny_ * nz_ > 4e8) throw ConfigError("exploration_box", "too large for the grid planner");
  blocked_.assign(size_t(nx_) * ny_ * nz_, 0);
  setWindow({0, 0, 0}, {nx_, ny_, nz_});
}

void GridPathPlanner::setWindow(const std::array<int, 3>& lo, const std::array<int, 3>& hi) {
  win_lo_ = lo;
  win_hi_ = hi;
}

bool GridPathPlanner::cellOf(const Vec3& p, int* i, int* j, int* k) const {
  const Vec3 q = (p - origin_) / res_;
  *i = int(std::floor(q.x()));
  *j = int(std::floor(q.y()));
  *k = int(std::floor(q.z()));
  return *i >= 0 && *j >= 0 && *k >= 0 && *i < nx_ && *j < ny_ && *k < nz_;
}

Vec3 GridPathPlanner::centre(int i, int j, int k) const { return origin_ + res_ * Vec3(i + 0.5, j + 0.5, k + 0.5); }

bool GridPathPlanner::traversable(const Vec3& p) const {
  int i, j, k;
  return cellOf(p, &i, &j, &k) && inWindow(i, j, k) && !(blocked_[size_t(index(i, j, k))] & kBlocked);
}

long GridPathPlanner::blockedCells() const {
  return long(std::count_if(blocked_.begin(), blocked_.end(), [](uint8_t b) { return b & kBlocked; }));
}

void GridPathPlanner::rebuild(const GridMap& map, const std::optional<Vec3>& start) {
  std::fill(blocked_.begin(), blocked_.end(), 0);
  setWindow({0, 0, 0}, {nx_, ny_, nz_});
  tree_work_ = {};
  if (usesPlanningTree()) {
    if (!start) throw std::logic_error("GridPathPlanner: a planning tree is rebuilt around a start");
    rebuildFromPlanningTree(map, *start);
    return;
  }
  blockAroundOccupied(map);
  // Optionally (the paper's rule), unknown space is not traversable either.
  if (config_.unknown_is_occupied) blockUnknown(knownCells(map));
}

void GridPathPlanner::rebuildFromPlanningTree(const GridMap& map, const Vec3& start) {
  // createPlanningTree: a tree of the planning resolution with the mapping tree's thresholds;
  // its origin cell set to log-odds 0 (at the default threshold: occupied) before every touch.
  const octomap::OcTree& src = map.tree();
  octomap::OcTree tree(res_);
  tree.setOccupancyThres(src.getOccupancyThres());
  const octomap::OcTreeKey origin = tree.coordToKey(0, 0, 0, tree.getTreeDepth());
  const Vec3 lo = start - Vec3::Constant(kPlanningTreeSubmapM), hi = start + Vec3::Constant(kPlanningTreeSubmapM);
  for (auto it = src.begin_leafs_bbx(octomap::point3d(float(lo.x()), float(lo.y()), float(lo.z())),
                                     octomap::point3d(float(hi.x()), float(hi.y()), float(hi.z()))),
            end = src.end_leafs_bbx();
       it != end; ++it) {
    tree.setNodeValue(origin, 0.0f);
    // The leaf's centre keyed in the new tree, its node touched at the leaf's own depth.
    const octomap::OcTreeKey key = tree.coordToKey(it.getX(), it.getY(), it.getZ());
    octomap::OcTreeNode* node = tree.getRoot();
    for (unsigned depth = 0; depth < it.getDepth(); ++depth) {
      const unsigned pos = octomap::computeChildIdx(key, int(tree.getTreeDepth() - depth - 1));
      if (!tree.nodeChildExists(node, pos)) tree.createNodeChild(node, pos);
      node = tree.getNodeChild(node, pos);
    }
    node->setLogOdds(src.isNodeOccupied(*it) ? 1.0f : -1.0f);
    ++tree_work_.leaves;
  }
  tree.expand();
  // The distance field spans the tree's metric box, the origin's cell included.
  double x0, y0, z0, x1, y1, z1;
  tree.getMetricMin(x0, y0, z0);
  tree.getMetricMax(x1, y1, z1);
  tree_work_.edt_cells = (x1 - x0) * (y1 - y0) * (z1 - z0) / (res_ * res_ * res_);
  // Its leaves as cells: known, and occupied ones blocking their clearance.
  std::vector<uint8_t> known(blocked_.size(), 0);
  const std::vector<std::array<int, 4>> offsets = offsetsWithin(config_.clearance_m);
  std::array<int, 3> klo{nx_, ny_, nz_}, khi{0, 0, 0};
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    ++tree_work_.cells;
    int i, j, k;
    if (!cellOf(Vec3(it.getX(), it.getY(), it.getZ()), &i, &j, &k)) continue;
    known[size_t(index(i, j, k))] = 1;
    klo = {std::min(klo[0], i), std::min(klo[1], j), std::min(klo[2], k)};
    khi = {std::max(khi[0], i + 1), std::max(khi[1], j + 1), std::max(khi[2], k + 1)};
    if (tree.isNodeOccupied(*it)) blockAroundCell(i, j, k, offsets);
  }
  if (!config_.unknown_is_occupied) return;
  // Unknown cells blocked: nothing outside the known cells' extent can be passed, so the
  // search keeps to it (and blockUnknown to the cells bordering it).
  // The window is that extent and the unknown cells around it (a start there may step in).
  if (klo[0] >= khi[0]) {  // no known cell: nothing to plan through
    setWindow({0, 0, 0}, {0, 0, 0});
    return;
  }
  setWindow({std::max(0, klo[0] - 1), std::max(0, klo[1] - 1), std::max(0, klo[2] - 1)},
            {std::min(nx_, khi[0] + 1), std::min(ny_, khi[1] + 1), std::min(nz_, khi[2] + 1)});
  blockUnknown(known);
}

void GridPathPlanner::blockAroundCell(int ci, int cj, int ck, const std::vector<std::array<int, 4>>& offsets) {
  for (const auto& o : offsets) {
    const int i = ci + o[0], j = cj + o[1], k = ck + o[2];
    if (i < 0 || j < 0 || k < 0 || i >= nx_ || j >= ny_ || k >= nz_) continue;
    blocked_[size_t(index(i, j, k))] |= uint8_t(o[3]);
  }
}

std::vector<std::array<int, 4>> GridPathPlanner::offsetsWithin(double clearance_m) const {
  // Offsets of the cells whose centres lie within a distance of a cell centre, with the flags
  // they get: kBlocked within the clearance, kBlocked | kHard within the escape clearance.
  const double hard_m = std::min(config_.escape_clearance_m, clearance_m);
  const int r = int(std::floor(clearance_m / res_ + 1e-9));
  std::vector<std::array<int, 4>> offsets;
  for (int dz = -r; dz <= r; ++dz)
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        const double d = res_ * std::sqrt(double(dx * dx + dy * dy + dz * dz));
        const int flags = (d <= clearance_m + 1e-9 ? kBlocked : 0) | (d <= hard_m + 1e-9 ? kBlocked | kHard : 0);
        if (flags) offsets.push_back({dx, dy, dz, flags});
      }
  return offsets;
}

void GridPathPlanner::blockAroundOccupied(const GridMap& map) {
  // Every occupied cell (a pruned leaf covers several) blocks its neighbourhood.
  const std::vector<std::array<int, 4>> offsets = offsetsWithin(config_.clearance_m);
  const Vec3 margin = Vec3::Constant(config_.clearance_m + res_);
  for (const GridLeaf& leaf : map.leaves(true)) {
    const double h = 0.5 * leaf.size_m;
    if (((leaf.centre.array() + h) < (box_.min - margin).array()).any() ||
        ((leaf.centre.array() - h) > (box_.max + margin).array()).any())
      continue;
    const int n = std::max(1, int(std::lround(leaf.size_m / res_)));
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        for (int c = 0; c < n; ++c) {
          const Vec3 cell = leaf.centre - Vec3::Constant(h) + res_ * Vec3(a + 0.5, b + 0.5, c + 0.5);
          const Vec3 q = (cell - origin_) / res_;
          blockAroundCell(int(std::floor(q.x())), int(std::floor(q.y())), int(std::floor(q.z())), offsets);
        }
  }
}

std::vector<uint8_t> GridPathPlanner::knownCells(const GridMap& map) const {
  // The cells any leaf of the map (free or occupied) covers.
  std::vector<uint8_t> known(blocked_.size(), 0);
  for (auto it = map.tree().begin_leafs_bbx(
                octomap::point3d(float(origin_.x()), float(origin_.y()), float(origin_.z())),
                octomap::point3d(float(origin_.x() + nx_ * res_), float(origin_.y() + ny_ * res_),
                                 float(origin_.z() + nz_ * res_))),
            end = map.tree().end_leafs_bbx();
       it != end; ++it) {
    const Vec3 c(it.getX(), it.getY(), it.getZ());
    const double h = 0.5 * it.getSize();
    const int n = std::max(1, int(std::lround(it.getSize() / res_)));
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        for (int d = 0; d < n; ++d) {
          int i, j, k;
          if (cellOf(c - Vec3::Constant(h) + res_ * Vec3(a + 0.5, b + 0.5, d + 0.5), &i, &j, &k))
            known[size_t(index(i, j, k))] = 1;
        }
  }
  return known;
}

void GridPathPlanner::blockUnknown(const std::vector<uint8_t>& known) {
  // Unknown cells are blocked, and those bordering known cells block their neighbourhood (the
  // clearance is kept from unknown space too; the nearest unknown cell to a known one always
  // borders known space).
  const std::vector<std::array<int, 4>> unknown_offsets =
      offsetsWithin(config_.unknown_clearance_m < 0 ? config_.clearance_m : config_.unknown_clearance_m);
  static constexpr int kFaces[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  auto inside = [&](int a, int b, int c) { return a >= 0 && b >= 0 && c >= 0 && a < nx_ && b < ny_ && c < nz_; };
  std::vector<uint8_t> dilated = blocked_;
  // The window and the unknown cells bordering it (beyond them no cell borders a known one).
  const int i0 = std::max(0, win_lo_[0] - 1), j0 = std::max(0, win_lo_[1] - 1), k0 = std::max(0, win_lo_[2] - 1);
  const int i1 = std::min(nx_, win_hi_[0] + 1), j1 = std::min(ny_, win_hi_[1] + 1), k1 = std::min(nz_, win_hi_[2] + 1);
  for (int k = k0; k < k1; ++k)
    for (int j = j0; j < j1; ++j)
      for (int i = i0; i < i1; ++i) {
        if (known[size_t(index(i, j, k))]) continue;
        dilated[size_t(index(i, j, k))] |= kBlocked | kHard;  // unknown itself
        bool border = false;
        for (int f = 0; f < 6 && !border; ++f) {
          const int a = i + kFaces[f][0], b = j + kFaces[f][1], c = k + kFaces[f][2];
          border = inside(a, b, c) && known[size_t(index(a, b, c))];
        }
        if (!border) continue;
        for (const auto& o : unknown_offsets) {
          const int a = i + o[0], b = j + o[1], c = k + o[2];
          if (inside(a, b, c)) dilated[size_t(index(a, b, c))] |= uint8_t(o[3]);
        }
      }
  blocked_ = std::move(dilated);
}

bool GridPathPlanner::passable(int i, int j, int k, const Passability& p) const {
  const uint8_t b = blocked_[size_t(index(i, j, k))];
  if (!(b & kBlocked)) return true;
  return p.start_blocked && !(b & kHard) && (centre(i, j, k) - p.start_c).squaredNorm() <= p.escape2;
}

GridPathPlanner::Search GridPathPlanner::search(int64_t start, int64_t goal, const Passability& p,
                                                int max_expansions) const {
  // A* over the window's cells; g in metres, parent per cell; ties by the lower cell index.
  const size_t n = size_t(win_hi_[0] - win_lo_[0]) * size_t(win_hi_[1] - win_lo_[1]) * size_t(win_hi_[2] - win_lo_[2]);
  auto cellIjk = [&](int64_t c) {
    return std::array<int, 3>{int(c % nx_), int((c / nx_) % ny_), int(c / (int64_t(nx_) * ny_))};
  };
  auto local = [&](int64_t c) { return size_t(windowIndexOf(c)); };
  const Vec3 start_c = centre(start), goal_c = centre(goal);
  std::vector<float> g(n, std::numeric_limits<float>::infinity());
  Search s;
  s.parent.assign(n, -1);
  std::vector<uint8_t> closed(n, 0);
  using Entry = std::pair<double, int64_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  g[local(start)] = 0;
  const double h0 = (goal_c - start_c).norm();
  open.push({h0, start});
  s.best = start;
  // The best cells so far: msbench's (expanded, closest to the goal) and the reference's
  // (reached: lowest f, ties by the lower h, later ones winning; closest to the goal).
  double best_d = h0, ref_f = h0, ref_f_h = h0, ref_h = h0;
  int64_t ref_f_cell = start, ref_h_cell = start;
  const bool reference = config_.reference_search;
  while (!open.empty() && s.expansions < max_expansions) {
    const auto [f, cur] = open.top();
    open.pop();
    if (closed[local(cur)]) continue;
    closed[local(cur)] = 1;
    ++s.expansions;
    const auto [ci, cj, ck] = cellIjk(cur);
    const double d_goal = (centre(ci, cj, ck) - goal_c).norm();
    if (d_goal < best_d - 1e-12) best_d = d_goal, s.best = cur;
    if (cur == goal) break;
    const double g_cur = g[local(cur)];
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (!dx && !dy && !dz) continue;
          const int i = ci + dx, j = cj + dy, k = ck + dz;
          if (!inWindow(i, j, k) || !passable(i, j, k, p)) continue;
          const size_t nb = size_t(windowIndex(i, j, k));
          if (closed[nb]) continue;
          const double ng = g_cur + res_ * std::sqrt(double(dx * dx + dy * dy + dz * dz));
          if (ng >= g[nb] || (reference && std::isfinite(g[nb]))) continue;  // the reference never re-opens
          g[nb] = float(ng);
          s.parent[nb] = cur;
          const double h = (centre(i, j, k) - goal_c).norm();
          open.push({ng + h, index(i, j, k)});
          if (ng + h < ref_f || (ng + h == ref_f && h <= ref_f_h))
            ref_f = ng + h, ref_f_h = h, ref_f_cell = index(i, j, k);
          if (h <= ref_h) ref_h = h, ref_h_cell = index(i, j, k);
        }
  }
  if (reference && s.best != goal) s.best = ref_f_cell != start ? ref_f_cell : ref_h_cell;
  return s;
}

bool GridPathPlanner::segmentClear(const Vec3& a, const Vec3& b, const Passability& p) const {
  auto cellPassable = [&](const Eigen::Vector3i& c) {
    return inWindow(c.x(), c.y(), c.z()) && passable(c.x(), c.y(), c.z(), p);
  };
  const Vec3 p0 = (a - origin_) / res_, d = (b - a) / res_;
  Eigen::Vector3i c = p0.array().floor().cast<int>();
  const Eigen::Vector3i last = (p0 + d).array().floor().cast<int>();
  Eigen::Vector3i step;
  Vec3 t_max, t_delta;
  for (int k = 0; k < 3; ++k) {
    step[k] = d[k] > 0 ? 1 : (d[k] < 0 ? -1 : 0);
    t_delta[k] = step[k] ? 1.0 / std::abs(d[k]) : 1e300;
    t_max[k] = step[k] ? ((c[k] + (step[k] > 0)) - p0[k]) / d[k] : 1e300;
  }
  for (int guard = 0; guard < 100000; ++guard) {
    if (!cellPassable(c)) return false;
    if (c == last) return true;
    const double t = t_max.minCoeff();
    if (t > 1.0) return true;
    bool tied[3];
    int n_tied = 0;
    for (int k = 0; k < 3; ++k) n_tied += (tied[k] = t_max[k] <= t + 1e-12);
    Eigen::Vector3i next = c;
    for (int k = 0; k < 3; ++k) {
      if (!tied[k]) continue;
      if (n_tied > 1) {  // through an edge or a corner: the cells beside it count too
        Eigen::Vector3i side = c;
        side[k] += step[k];
        if (!cellPassable(side)) return false;
      }
      next[k] += step[k];
      t_max[k] += t_delta[k];
    }
    c = next;
  }
  return false;
}

std::optional<GridPath> GridPathPlanner::plan(const Vec3& start_in, const Vec3& goal_in, int max_expansions) const {
  // Start and goal cells (clamped into the box; a start far outside cannot be planned from).
  auto clampCell = [&](const Vec3& p, int* i, int* j, int* k) {
    const Vec3 q = (p - origin_) / res_;
    *i = std::clamp(int(std::floor(q.x())), 0, nx_ - 1);
    *j = std::clamp(int(std::floor(q.y())), 0, ny_ - 1);
    *k = std::clamp(int(std::floor(q.z())), 0, nz_ - 1);
  };
  const Vec3 lo = origin_ - Vec3::Constant(res_), hi = origin_ + res_ * Vec3(nx_ + 1, ny_ + 1, nz_ + 1);
  if ((start_in.array() < lo.array()).any() || (start_in.array() > hi.array()).any()) return std::nullopt;
  int si, sj, sk, gi, gj, gk;
  clampCell(start_in, &si, &sj, &sk);
  clampCell(goal_in, &gi, &gj, &gk);
  const int64_t start = index(si, sj, sk), goal = index(gi, gj, gk);
  // A vehicle already in blocked cells may leave through blocked cells near it, but never
  // through hard ones (occupied, unknown with unknown_is_occupied, or within the escape clearance).
  Passability pass;
  pass.start_blocked = blocked_[size_t(start)] & kBlocked;
  pass.start_c = centre(si, sj, sk);
  pass.escape2 = config_.escape_radius_m * config_.escape_radius_m;
  // A start outside the window (no known cell near it) cannot move.
  GridPath out;
  if (!inWindow(si, sj, sk)) {
    out.points.push_back(start_in);
    return out;
  }
  const int budget = max_expansions >= 0 ? std::min(max_expansions, config_.max_expansions) : config_.max_expansions;
  const Search s = search(start, goal, pass, budget);

  // Cells from the start to the goal (or the reached cell closest to it).
  out.reaches_goal = s.best == goal;
  out.expansions = s.expansions;
  std::vector<Vec3> cells;
  for (int64_t c = s.best; c >= 0; c = s.parent[size_t(windowIndexOf(c))]) cells.push_back(centre(c));
  std::reverse(cells.begin(), cells.end());
  cells.front() = start_in;
  if (out.reaches_goal && cells.size() > 1 && traversable(goal_in)) cells.back() = goal_in;

  // Line-of-sight shortcuts: from each kept point, the farthest later cell in clear sight.
  out.points.push_back(cells.front());
  size_t from = 0;
  while (from + 1 < cells.size()) {
    size_t to = cells.size() - 1;
    while (to > from + 1 && !segmentClear(cells[from], cells[to], pass)) --to;
    out.points.push_back(cells[to]);
    from = to;
  }
  return out;
}

}  // namespace msb
