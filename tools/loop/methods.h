// The exploration methods the loop can run, as plain C++ (no YAML): each method is one
// function that turns its validated config into a MethodChoice. The YAML side of the method
// table (tools/config/method_table.cc) reads a scenario's `method:` keys for the chosen type
// and calls the function here; tests call it directly.
#pragma once

#include <any>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "core/baseline/grid_explorer.h"
#include "core/baseline/star_discovery_explorer.h"
#include "core/camera/fisheye_camera.h"
#include "core/planning/explorer.h"
#include "core/planning/monospheres_explorer.h"

namespace msb {

/// The `method.type` names, written once (the factories below and the method table use them).
inline constexpr char kMonoSpheresType[] = "monospheres";
inline constexpr char kGridRandomType[] = "grid_random";
inline constexpr char kStarDiscoveryType[] = "star_discovery";

/// The method of a scenario: its type, its validated config and a factory.
struct MethodChoice {
  std::string type;                       ///< as in `method.type`
  std::any config;                        ///< the method's config struct (e.g. MonoSpheresConfig)
  std::map<std::string, bool> switches;   ///< the method's on/off switches, for reports
  /// Creates the explorer for a mission.
  std::function<std::unique_ptr<Explorer>(const FisheyeCamera&, const ExplorerContext&)> make;
};

/// MonoSpheres (`monospheres`): the sphere map and its planner; switches ovde, dbof, fff, vpb.
MethodChoice monospheresMethod(const MonoSpheresConfig& config = {});
/// The grid baseline (`grid_random`): OctoMap, random goals, grid A*.
MethodChoice gridRandomMethod(const GridExplorerConfig& config = {});
/// Star discovery (von Stumberg et al.) on the grid baseline's map.
MethodChoice starDiscoveryMethod(const StarDiscoveryConfig& config = {});

}  // namespace msb
