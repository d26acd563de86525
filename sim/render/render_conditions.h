// Changing conditions of light and visibility (the HARDNAV simulator's "global directional light
// of varying intensity, colour, angle; fog of varying colour and density"), applied by the
// renderer to the world's sun, the ambient light, the sky and GL fog. Deterministic: they only
// change model and GL state set once when the renderer is built. docs/conditions.md.
//
// Unset fields (NaN, fog_end_m = 0) keep the world's own lighting, so the default conditions
// render exactly as before.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "core/common/config_fields.h"

namespace msb {

/// Light and visibility of a scene; NaN = the world's own value.
struct RenderConditions {
  double sun_elevation_deg = NAN;                      ///< sun above the horizon, (0, 90]
  double sun_azimuth_deg = NAN;                        ///< direction the sun stands in, from +x towards +y
  double sun_intensity = NAN;                          ///< diffuse intensity of the sun, [0, 1.5] (worlds: 0.45)
  std::array<double, 3> sun_colour = {1.0, 1.0, 1.0};  ///< RGB multiplier of the sun, [0, 1]
  double ambient = NAN;         ///< ambient light level, [0, 1] (worlds: 0.55 with sun, 0.9 without)
  double sky_brightness = NAN;  ///< grey level of the sky, [0, 1] (worlds: saturated white)
  double fog_start_m = 0.0;     ///< linear fog from this distance ...
  double fog_end_m = 0.0;       ///< ... to full fog colour at this one; 0 = no fog
  std::array<double, 3> fog_colour = {0.75, 0.75, 0.75};  ///< RGB of the fog, [0, 1]

  /// True if anything differs from the world's own lighting.
  bool changesAnything() const;
  /// The keys, each once with the values it accepts (NaN: unset, the world keeps its own; `preset` is read in
  /// tools/config).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("sun_elevation_deg", s.sun_elevation_deg, Limits::range(0.5, 90.0).orUnset());
    v.key("sun_azimuth_deg", s.sun_azimuth_deg, Limits::range(-360.0, 360.0).orUnset());
    v.key("sun_intensity", s.sun_intensity, Limits::range(0.0, 1.5).orUnset());
    v.key("sun_colour", s.sun_colour, Limits::range(0.0, 1.0));
    v.key("ambient", s.ambient, Limits::range(0.0, 1.0).orUnset());
    v.key("sky_brightness", s.sky_brightness, Limits::range(0.0, 1.0).orUnset());
    v.key("fog_start_m", s.fog_start_m, Limits::nonNegative());
    v.key("fog_end_m", s.fog_end_m, Limits::nonNegative());
    v.key("fog_colour", s.fog_colour, Limits::range(0.0, 1.0));
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// The named presets: default, noon, low_sun, dusk, overcast, haze, fog, dusk_haze.
std::optional<RenderConditions> conditionsPreset(const std::string& name);
/// The preset names, in order.
std::vector<std::string> conditionsPresetNames();

}  // namespace msb
