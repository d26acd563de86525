// The exploration method of a mission as the loop sees it: a type name, a validated config and
// a factory. MethodChoice is built from a method's config struct by methodChoice<Explorer>(),
// which is generic. The methods themselves are listed in the method table
// (tools/config/method_table.cc), one entry each; the one method named here is MonoSpheres, the
// paper's method, as the default of a C++-built ScenarioSpec (monospheresMethod() below).
#pragma once

#include <any>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>

#include "core/camera/fisheye_camera.h"
#include "core/common/config_check.h"
#include "core/explorer/explorer.h"
#include "core/planning/monospheres_explorer.h"

namespace msb {

/// The method of a scenario: its type, its validated config and a factory.
struct MethodChoice {
  std::string type;                       ///< as in `method.type`
  std::any config;                        ///< the method's config struct (e.g. MonoSpheresConfig)
  std::map<std::string, bool> switches;   ///< the method's on/off switches (ablations), for reports
  /// Creates the explorer for a mission.
  std::function<std::unique_ptr<Explorer>(const FisheyeCamera&, const ExplorerContext&)> make;
};

/// The MethodChoice of `ExplorerT` with `config` (validated here; throws ConfigError). The
/// explorer is constructed from (config, camera, context) or (config, context); the switches are
/// the config's `switches()` if it has one (the paper's ablation switches), else none.
template <class ExplorerT, class Config>
MethodChoice methodChoice(std::string type, const Config& config) {
  const Config c = checkValid(config);
  MethodChoice m;
  m.type = std::move(type);
  m.config = c;
  if constexpr (requires { c.switches(); }) m.switches = c.switches();
  m.make = [c](const FisheyeCamera& camera, const ExplorerContext& context) -> std::unique_ptr<Explorer> {
    if constexpr (std::is_constructible_v<ExplorerT, const Config&, const FisheyeCamera&, const ExplorerContext&>)
      return std::make_unique<ExplorerT>(c, camera, context);
    else
      return std::make_unique<ExplorerT>(c, context);
  };
  return m;
}

/// The `method.type` of MonoSpheres (the default method).
inline constexpr char kMonoSpheresType[] = "monospheres";

/// MonoSpheres with `config` (the default method of a scenario).
inline MethodChoice monospheresMethod(const MonoSpheresConfig& config = {}) {
  return methodChoice<MonoSpheresExplorer>(kMonoSpheresType, config);
}

}  // namespace msb
