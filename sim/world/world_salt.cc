#include "sim/world/world_salt.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <vector>

#include "core/common/rng.h"

namespace msb {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The salt's own seed for the streams below (domain-separated from the commitment).
uint64_t saltSeed(const std::string& salt, const std::string& world) {
  const std::string text = "msbench world salt seed\n" + world + "\n" + salt;
  return fnv1a64(text.data(), text.size());
}

// Whether the start's heading lies along an axis (the box stays axis-aligned in the mirror).
bool alongAnAxis(double yaw_deg) {
  const double q = std::fmod(std::fmod(yaw_deg, 90.0) + 90.0, 90.0);
  return q < 1e-6 || q > 90.0 - 1e-6;
}

// How far a fixed object turns: buildings stand square to their streets (quarter turns);
// vehicles and walls keep their line within kVehicleTurnDeg (a bus turned across a street closes
// it); trees, rocks and the rest turn freely.
double turnOf(const std::string& kind, RngStream& rng) {
  if (kind == "building" || kind == "house" || kind == "gazebo" || kind == "tower")
    return 90.0 * double(rng.uniformInt(4));
  if (kind == "car" || kind == "suv" || kind == "bus" || kind == "fire_truck" || kind == "ambulance" ||
      kind == "wall" || kind == "dumpster")
    return rng.uniform(-kVehicleTurnDeg, kVehicleTurnDeg);
  return rng.uniform(0.0, 360.0);
}

// Whether a fixed object stands where moving it could touch the start's clearance or the take-off
// (it keeps its place and pose: the take-off is the world's own).
bool nearTheStart(const WorldSpec& s, const ObjectGroupSpec& g) {
  const double reach = 0.5 * g.size_max.head<2>().norm() + g.offset.norm();
  const double keep = std::max(s.start_clearance_m + s.start_corridor_m + kSaltJitterM + 3.0, kSaltKeepM);
  return (*g.at - s.start_position_m.head<2>()).norm() - reach < keep;
}

// Fixed objects (one each, `at` given) trade places within groups of the same kind and size.
void swapLikeObjects(WorldSpec& s, RngStream& rng, int& swapped) {
  std::map<std::string, std::vector<size_t>> like;
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const ObjectGroupSpec& g = s.objects[i];
    if (!g.at || g.count != 1 || !g.near.empty() || nearTheStart(s, g)) continue;
    char key[160];
    std::snprintf(key, sizeof(key), "%s|%.2f|%.2f|%.2f|%.2f|%.2f|%.2f|%s", g.kind.c_str(), g.size_min.x(),
                  g.size_min.y(), g.size_min.z(), g.size_max.x(), g.size_max.y(), g.size_max.z(), g.variant.c_str());
    like[key].push_back(i);
  }
  for (auto& [key, members] : like) {
    if (members.size() < 2) continue;
    std::vector<size_t> order(members.size());
    std::iota(order.begin(), order.end(), 0);
    for (size_t k = order.size() - 1; k > 0; --k) std::swap(order[k], order[rng.uniformInt(k + 1)]);
    std::vector<ObjectGroupSpec> before;
    for (size_t i : members) before.push_back(s.objects[i]);
    for (size_t k = 0; k < members.size(); ++k) {
      const ObjectGroupSpec& from = before[order[k]];
      ObjectGroupSpec& to = s.objects[members[k]];
      if (order[k] != k) ++swapped;
      to.at = from.at;
      to.yaw_deg = from.yaw_deg;
      to.base_z_m = from.base_z_m;
    }
  }
}

// Fixed objects moved by up to kSaltJitterM and turned; none that could reach the start's
// clearance (objects are kept where the spec's check of the start still holds).
void jitterObjects(WorldSpec& s, RngStream& rng, int& jittered) {
  for (ObjectGroupSpec& g : s.objects) {
    if (!g.at || !g.near.empty() || nearTheStart(s, g)) continue;
    const double r = kSaltJitterM * std::sqrt(rng.uniform()), a = rng.uniform(0.0, 2.0 * kPi);
    *g.at += r * Vec2(std::cos(a), std::sin(a));
    const double turn = turnOf(g.kind, rng);
    g.yaw_deg = std::remainder(g.yaw_deg.value_or(0.0) + turn, 360.0);
    ++jittered;
  }
}

// Everything the spec places, mirrored.
void mirrorSpec(WorldSpec& s, const WorldSalting& h) {
  for (ObjectGroupSpec& g : s.objects) {
    if (g.at) *g.at = h.point(*g.at);
    if (g.yaw_deg) g.yaw_deg = h.yaw(*g.yaw_deg * kPi / 180.0) * 180.0 / kPi;
    g.offset.y() = -g.offset.y();  // the solid's centre, in the object's (now mirrored) frame
    if (g.region_min && g.region_max) {
      const Vec2 a = h.point(*g.region_min), b = h.point(*g.region_max);
      g.region_min = a.cwiseMin(b);
      g.region_max = a.cwiseMax(b);
    }
  }
  for (MeshSpec& m : s.meshes) {
    const Vec2 at = h.point(m.at.head<2>());
    m.at.head<2>() = at;
    m.yaw_deg = h.yaw(m.yaw_deg * kPi / 180.0) * 180.0 / kPi;
    m.mirrored = !m.mirrored;  // a mirror is a turn and a flip of the mesh's own y
  }
  if (s.cave) {
    auto box2 = [&](Vec2& lo, Vec2& hi) {
      const Vec2 a = h.point(lo), b = h.point(hi);
      lo = a.cwiseMin(b);
      hi = a.cwiseMax(b);
    };
    box2(s.cave->min, s.cave->max);
    for (CaveChamberSpec& c : s.cave->chambers) box2(c.min, c.max);
    for (CaveTunnelSpec& t : s.cave->tunnels) {
      t.from = h.point(t.from);
      t.to = h.point(t.to);
    }
  }
  s.exploration_box = h.box(s.exploration_box);
  // The sun, mirrored: every face lit as its mirror image was.
  const Vec2 sun = s.sun_direction.head<2>(), n(-h.heading.y(), h.heading.x());
  s.sun_direction.head<2>() = sun.dot(h.heading) * h.heading - sun.dot(n) * n;
  // The ground (centred on the origin) grows to lie under the mirrored box.
  const Vec2 reach = s.exploration_box.min.head<2>().cwiseAbs().cwiseMax(s.exploration_box.max.head<2>().cwiseAbs());
  s.ground_size_m = s.ground_size_m.cwiseMax(2.0 * reach + Vec2::Constant(2.0));
}

}  // namespace

Vec2 WorldSalting::point(const Vec2& p) const {
  if (!mirrored) return p;
  const Vec2 d = p - origin, n(-heading.y(), heading.x());
  return origin + d.dot(heading) * heading - d.dot(n) * n;
}

double WorldSalting::yaw(double yaw_rad) const {
  if (!mirrored) return yaw_rad;
  return std::remainder(2.0 * std::atan2(heading.y(), heading.x()) - yaw_rad, 2.0 * kPi);
}

Aabb WorldSalting::box(const Aabb& b) const {
  if (!mirrored) return b;
  const Vec2 a = point(b.min.head<2>()), c = point(b.max.head<2>());
  Aabb out = b;
  out.min.head<2>() = a.cwiseMin(c);
  out.max.head<2>() = a.cwiseMax(c);
  return out;
}

WorldSpec saltWorldSpec(const WorldSpec& spec, const std::string& salt, WorldSalting* how) {
  WorldSpec s = spec;
  WorldSalting h;
  RngStream rng(saltSeed(salt, spec.name), "world_salt");
  s.seed = rng.bits() >> 1;  // objects placed at random: placed anew
  h.texture_seed = rng.bits() | 1;
  s.texture_seed = h.texture_seed;
  // Fixed objects on a terrain mesh stand at its heights: they stay where they are.
  if (s.meshes.empty()) {
    swapLikeObjects(s, rng, h.swapped);
    jitterObjects(s, rng, h.jittered);
  }
  h.origin = s.start_position_m.head<2>();
  h.heading = Vec2(std::cos(s.start_yaw_deg * kPi / 180.0), std::sin(s.start_yaw_deg * kPi / 180.0));
  h.mirrored = rng.uniform() < 0.5 && alongAnAxis(s.start_yaw_deg);
  if (h.mirrored) {
    h.heading = h.heading.array().round();  // exactly along its axis
    mirrorSpec(s, h);
  }
  if (how) *how = h;
  return s;
}

std::string worldSaltCommitment(const std::string& salt) {
  const std::string text = "msbench world salt commitment\n" + salt;
  char hex[32];
  std::snprintf(hex, sizeof(hex), "fnv1a64:%016llx",
                static_cast<unsigned long long>(fnv1a64(text.data(), text.size())));
  return hex;
}

}  // namespace msb
