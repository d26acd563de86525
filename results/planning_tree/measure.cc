// What mrs_octomap_planner's 0.4 m planning tree does to a 0.5 m map (issue 91, item 1): the
// planner resamples the mapping tree's leaves into a tree of `planning_tree/resolution` 0.4 m
// (astar_planner.cpp createPlanningTree, 428-466: each leaf's centre keyed in the new tree and
// touched at the leaf's own depth, then expand()), and its A* expands a key only where the
// planning tree has a FREE node (getNeighborhood, 282-300). This program builds a 0.5 m OcTree
// with liboctomap from synthetic sparse-SLAM-like scans (rays from a camera flying a loop to
// random points on the ground and on the walls of a 60 × 60 × 8 m yard with four blocks), pruned
// as mrs_octomap_server's map is (or not), resamples it as createPlanningTree does, and counts
// (1) the key planes of the planning tree inside the mapped volume that hold no node at all,
// (2) the free volume reachable from the start through 26-neighbours, in the 0.5 m map and in
// the 0.4 m planning tree. The EDF inflation is left out: it can only remove more cells.
//   g++ -O2 -std=c++20 results/planning_tree/measure.cc -loctomap -loctomath -o /tmp/measure
//   /tmp/measure > results/planning_tree/output.txt
#include <octomap/OcTree.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <deque>
#include <random>
#include <set>

using octomap::OcTree;
using octomap::OcTreeKey;
using octomap::point3d;

namespace {

// The yard: ground z = 0, walls at ±30 m up to 8 m, four 10 × 10 × 6 m blocks.
struct Box {
  double x0, y0, x1, y1, z1;
};
const std::array<Box, 4> kBlocks = {
    {{-20, -20, -10, -10, 6}, {10, -20, 20, -10, 6}, {-20, 10, -10, 20, 6}, {10, 10, 20, 20, 6}}};

bool insideBlock(const point3d& p) {
  for (const Box& b : kBlocks)
    if (p.x() > b.x0 && p.x() < b.x1 && p.y() > b.y0 && p.y() < b.y1 && p.z() < b.z1) return true;
  return false;
}

// First hit of a ray from o along d (unit) within 15 m, marched at 5 cm, or nothing.
bool castRay(const point3d& o, const point3d& d, point3d* hit) {
  for (double t = 0.05; t < 15.0; t += 0.05) {
    const point3d p = o + d * float(t);
    if (p.z() <= 0 || std::abs(p.x()) >= 30 || std::abs(p.y()) >= 30 || p.z() >= 8 || insideBlock(p)) {
      *hit = p;
      return true;
    }
  }
  return false;
}

// The map: a camera at 2.5 m flying the loop between the blocks, 150 rays a frame to random
// directions in its forward half-space (sparse SLAM points: one per ray that hits).
void buildMap(OcTree& tree, bool prune) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int frame = 0; frame < 400; ++frame) {
    const double a = 2 * M_PI * frame / 400.0;
    const point3d o(float(24 * std::cos(a)), float(24 * std::sin(a)), 2.5f);
    const point3d fwd(float(-std::sin(a)), float(std::cos(a)), 0.f);
    octomap::Pointcloud cloud;
    for (int k = 0; k < 150; ++k) {
      point3d d(float(u(rng)), float(u(rng)), float(0.5 * u(rng)));
      if (d.dot(fwd) < 0) d -= fwd * (2 * d.dot(fwd));
      d.normalize();
      point3d hit;
      if (castRay(o, d, &hit)) cloud.push_back(hit);
    }
    tree.insertPointCloud(cloud, o, 15.0, /*lazy_eval=*/!prune);
  }
  if (prune) {
    tree.updateInnerOccupancy();
    tree.prune();
  } else {
    tree.updateInnerOccupancy();
  }
}

// createPlanningTree's resampling (without the EDF and the tunnel).
void resample(const OcTree& tree, OcTree& out) {
  out.setNodeValue(out.coordToKey(0, 0, 0, out.getTreeDepth()), 0.0);
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    const OcTreeKey key = out.coordToKey(it.getX(), it.getY(), it.getZ());
    octomap::OcTreeNode* node = out.getRoot();
    for (unsigned depth = 0; depth < it.getDepth(); ++depth) {
      const unsigned pos = octomap::computeChildIdx(key, int(out.getTreeDepth() - depth - 1));
      if (!out.nodeChildExists(node, pos)) out.createNodeChild(node, pos);
      node = out.getNodeChild(node, pos);
    }
    node->setLogOdds(tree.isNodeOccupied(*it) ? 1.0f : -1.0f);
  }
  out.expand();
}

// Free volume (m³) reachable from `start` through 26-neighbours whose node exists and is free,
// within 1…7 m of height (the box band).
double reachable(const OcTree& t, const point3d& start) {
  const double r = t.getResolution();
  std::set<OcTreeKey, bool (*)(const OcTreeKey&, const OcTreeKey&)> seen(
      [](const OcTreeKey& a, const OcTreeKey& b) { return std::tie(a[0], a[1], a[2]) < std::tie(b[0], b[1], b[2]); });
  std::deque<OcTreeKey> open = {t.coordToKey(start)};
  seen.insert(open.front());
  while (!open.empty()) {
    const OcTreeKey k = open.front();
    open.pop_front();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          OcTreeKey n(k[0] + dx, k[1] + dy, k[2] + dz);
          const auto* node = t.search(n);
          const double z = t.keyToCoord(n).z();
          if (!node || t.isNodeOccupied(node) || z < 1.0 || z > 7.0 || seen.count(n)) continue;
          seen.insert(n);
          open.push_back(n);
        }
  }
  return double(seen.size()) * r * r * r;
}

// Key planes (x = const) crossing the mapped free volume that hold no node of the tree.
void emptyPlanes(const OcTree& t, int* empty, int* planes) {
  *empty = *planes = 0;
  const double r = t.getResolution();
  for (double x = -28; x <= 28; x += r) {
    const OcTreeKey kx = t.coordToKey(point3d(float(x), 0, 2.5f));
    ++*planes;
    bool any = false;
    for (double y = -28; y <= 28 && !any; y += r)
      for (double z = 1.0; z <= 4.0 && !any; z += r) {
        OcTreeKey k = t.coordToKey(point3d(float(x), float(y), float(z)));
        k[0] = kx[0];
        any = t.search(k) != nullptr;
      }
    *empty += !any;
  }
}

void report(bool prune) {
  OcTree map(0.5);
  buildMap(map, prune);
  size_t free_leaves = 0, big = 0;
  for (auto it = map.begin_leafs(); it != map.end_leafs(); ++it)
    if (!map.isNodeOccupied(*it)) ++free_leaves, big += it.getDepth() < map.getTreeDepth();
  OcTree plan(0.4);
  resample(map, plan);
  int empty = 0, planes = 0;
  emptyPlanes(plan, &empty, &planes);
  int empty_map = 0, planes_map = 0;
  emptyPlanes(map, &empty_map, &planes_map);
  const point3d start(24, 0, 2.5);
  std::printf("%s map: %zu free leaves (%zu of them pruned, above 0.5 m)\n", prune ? "pruned" : "unpruned", free_leaves,
              big);
  std::printf("  x key planes with no node, |x| <= 28 m, z 1-4 m: 0.5 m map %d of %d; 0.4 m planning tree %d of %d\n",
              empty_map, planes_map, empty, planes);
  std::printf(
      "  free volume reachable from (24, 0, 2.5) through known free neighbours, z 1-7 m: "
      "0.5 m map %.0f m^3; 0.4 m planning tree %.0f m^3\n",
      reachable(map, start), reachable(plan, start));
}

}  // namespace

int main() {
  report(false);
  report(true);
  return 0;
}
