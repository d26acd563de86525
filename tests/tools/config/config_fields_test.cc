// Every field of every configuration section is a key of the effective configuration: the number
// of a struct's fields (counted at compile time by aggregate initialisation) equals the number of
// keys its section writes, so a field left out of its keys function fails here. Sections that
// write a field elsewhere (render's conditions, written as the top-level `conditions`) say so.
#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <fstream>

#include <yaml-cpp/yaml.h>

#include "core/methods/grid_random/grid_explorer.h"
#include "core/methods/monospheres/map/sphere_map.h"
#include "core/methods/monospheres/planner/monospheres_explorer.h"
#include "tools/config/scenario_yaml.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

// Converts to any member type: T{AnyField{}, ...} compiles for as many initialisers as T has
// fields (one per field; nested structs and arrays count once).
struct AnyField {
  template <class T>
  constexpr operator T() const;  // never defined: only used in unevaluated requires-expressions
};

template <class T, class... A>
constexpr size_t fieldCount() {
  if constexpr (requires { T{A{}..., AnyField{}}; })
    return fieldCount<T, A..., AnyField>();
  else
    return sizeof...(A);
}

static_assert(fieldCount<FrontendDegradationConfig>() == 5, "the counter counts fields");

// The effective configuration of a default mission, parsed.
YAML::Node effective() {
  const fs::path d = fs::path(::testing::TempDir()) / "msb_config_fields";
  fs::create_directories(d);
  // Conditions with every field set (unset ones, NaN, are not written: the world's own light).
  std::ofstream(d / "s.yaml") << "world: urban\nconditions: {sun_elevation_deg: 30, sun_azimuth_deg: 10, "
                                 "sun_intensity: 1, ambient: 0.5, sky_brightness: 0.8}\n";
  return YAML::Load(effectiveScenarioYaml(loadScenario((d / "s.yaml").string())));
}

// Keys written under `path` ("a.b").
size_t keysAt(const YAML::Node& root, const std::string& path) {
  YAML::Node n = YAML::Clone(root);
  size_t from = 0;
  while (from <= path.size()) {
    const size_t dot = path.find('.', from);
    const std::string k = path.substr(from, dot == std::string::npos ? std::string::npos : dot - from);
    n = YAML::Node(n[k]);
    if (!n.IsDefined()) return 0;
    if (dot == std::string::npos) break;
    from = dot + 1;
  }
  return n.IsMap() ? n.size() : 0;
}

TEST(ConfigFields, EveryFieldOfEverySectionIsWrittenAsAKey) {
  const YAML::Node e = effective();
  EXPECT_EQ(keysAt(e, "frontend"), fieldCount<FrontendDegradationConfig>());
  EXPECT_EQ(keysAt(e, "vio_drift"), fieldCount<VioDriftConfig>());
  EXPECT_EQ(keysAt(e, "tracker"), fieldCount<FeatureTrackerConfig>());
  EXPECT_EQ(keysAt(e, "slam_points"), fieldCount<SlamPointsConfig>());
  EXPECT_EQ(keysAt(e, "imu"), fieldCount<ImuConfig>());
  EXPECT_EQ(keysAt(e, "camera_stream"), fieldCount<CameraStreamConfig>());
  EXPECT_EQ(keysAt(e, "perception"), fieldCount<PerceptionConfig>());
  EXPECT_EQ(keysAt(e, "perception.oracle"), fieldCount<OracleFeatureConfig>());
  EXPECT_EQ(keysAt(e, "conditions"), fieldCount<RenderConditions>());
  // render.conditions is written as the top-level `conditions` section.
  EXPECT_EQ(keysAt(e, "render") + 1, fieldCount<FisheyeRendererConfig>());
  EXPECT_EQ(keysAt(e, "controller"), fieldCount<Se3ControllerConfig>());
  EXPECT_EQ(keysAt(e, "physics"), fieldCount<PhysicsConfig>());
  EXPECT_EQ(keysAt(e, "physics.vehicle"), fieldCount<QuadrotorConfig>());
  EXPECT_EQ(keysAt(e, "camera"), fieldCount<FisheyeCameraConfig>());
  EXPECT_EQ(keysAt(e, "mission"), fieldCount<MissionSettings>());
}

// The effective configuration of a default mission with method `type`, parsed.
YAML::Node effectiveOf(const std::string& type) {
  const fs::path d = fs::path(::testing::TempDir()) / "msb_config_fields";
  fs::create_directories(d);
  std::ofstream(d / "m.yaml") << "world: urban\nmethod: {type: " << type << "}\n";
  return YAML::Load(effectiveScenarioYaml(loadScenario((d / "m.yaml").string())));
}

TEST(ConfigFields, TheMethodSectionsWriteEveryField) {
  // The grid baseline: its map and planner sections, and its own keys beside the take-off's two
  // and the path check's two (each base class counts as one field) and the two sections.
  const YAML::Node g = effectiveOf("grid_random");
  EXPECT_EQ(keysAt(g, "method.map"), fieldCount<GridMapConfig>());
  EXPECT_EQ(keysAt(g, "method.planner"), fieldCount<GridPlannerConfig>());
  EXPECT_EQ(keysAt(g, "method") - 1 /* type */ - 2 /* take-off */ - 2 /* path check */ + 2 /* bases */,
            fieldCount<GridExplorerConfig>());
  // MonoSpheres: the mapper's OVDE parameters, and the viewpoint section.
  const YAML::Node m = effectiveOf("monospheres");
  EXPECT_EQ(keysAt(m, "method.map.ovde_params"), fieldCount<OpenAreaDepthConfig>());
  // The mapper: its section plus the two switches written under method.switches (ovde, dbof).
  // and the six that method.reference_code sets (pinhole_rays, worked_mask_scalar,
  // early_return_stale, dbof_on_ovde_polyhedron, ovde_parallax_frames, dbof_pinhole_projection).
  EXPECT_EQ(keysAt(m, "method.map") + 2 + 6, fieldCount<SphereMapConfig>());
  // The planner: its section plus fff (under method.switches), its take-off and path-check keys
  // counted as one base each; viewpoints plus vpb (a switch); safety plus r_min_m, which is
  // method.map.r_min_m; each plus the published-code switch it takes from method.reference_code.
  // Its goal-choice, graph-repair and clearance parts are written flat beside its own keys.
  EXPECT_EQ(keysAt(m, "method.planner") + 1 - 2 - 2 + 2,
            fieldCount<MonoSpheresPlannerConfig>() - 3 + fieldCount<GoalChoiceConfig>() +
                fieldCount<GraphRepairConfig>() + fieldCount<ClearanceConfig>());
  EXPECT_EQ(keysAt(m, "method.planner.viewpoints") + 1 + 2 /* viewpoints_anywhere, pinhole_rays */,
            fieldCount<ViewpointConfig>());
  EXPECT_EQ(keysAt(m, "method.planner.safety") + 1 + 1, fieldCount<SafetyCostConfig>());
  EXPECT_EQ(keysAt(m, "method.reference_code"), fieldCount<ReferenceCodeConfig>());
  EXPECT_EQ(keysAt(m, "method.reference_code"), ReferenceCodeConfig::switches().size());
}

}  // namespace
}  // namespace msb
