#include "sim/render/render_conditions.h"

namespace msb {

bool RenderConditions::changesAnything() const {
  return !std::isnan(sun_elevation_deg) || !std::isnan(sun_azimuth_deg) || !std::isnan(sun_intensity) ||
         sun_colour != std::array<double, 3>{1.0, 1.0, 1.0} || !std::isnan(ambient) || !std::isnan(sky_brightness) ||
         fog_end_m > 0.0;
}

void RenderConditions::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require(fog_end_m == 0.0 || fog_end_m > fog_start_m, "fog_end_m", "must exceed fog_start_m (or be 0: no fog)");
}

std::optional<RenderConditions> conditionsPreset(const std::string& name) {
  RenderConditions c;
  if (name == "default") return c;
  if (name == "noon") {  // the sun high: roofs bright, walls alike
    c.sun_elevation_deg = 75, c.sun_azimuth_deg = 200, c.sun_intensity = 0.5;
    return c;
  }
  if (name == "low_sun") {  // grazing light: strong differences between faces, dark sides
    c.sun_elevation_deg = 8, c.sun_azimuth_deg = 30, c.sun_intensity = 0.7, c.ambient = 0.35;
    return c;
  }
  if (name == "dusk") {  // weak, orange light from the horizon; dim sky; little ambient
    c.sun_elevation_deg = 3, c.sun_azimuth_deg = 250, c.sun_intensity = 0.3;
    c.sun_colour = {1.0, 0.6, 0.35}, c.ambient = 0.22, c.sky_brightness = 0.35;
    return c;
  }
  if (name == "overcast") {  // no direct sun: every face as bright as every other
    c.sun_intensity = 0.0, c.ambient = 0.75, c.sky_brightness = 0.8;
    return c;
  }
  if (name == "haze") {  // far things fade: contrast drops with distance beyond 20 m
    c.fog_start_m = 20, c.fog_end_m = 150, c.fog_colour = {0.8, 0.8, 0.8};
    return c;
  }
  if (name == "fog") {  // dense fog: nothing beyond 40 m
    c.fog_start_m = 4, c.fog_end_m = 40, c.fog_colour = {0.75, 0.75, 0.75};
    return c;
  }
  if (name == "dusk_haze") {
    c = *conditionsPreset("dusk");
    c.fog_start_m = 15, c.fog_end_m = 120, c.fog_colour = {0.35, 0.3, 0.3};
    return c;
  }
  return std::nullopt;
}

std::vector<std::string> conditionsPresetNames() {
  return {"default", "noon", "low_sun", "dusk", "overcast", "haze", "fog", "dusk_haze"};
}

}  // namespace msb
