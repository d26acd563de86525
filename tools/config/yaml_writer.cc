#include "tools/config/yaml_writer.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "core/common/types.h"

namespace msb {

std::string exactNumberText(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  if (r.ec != std::errc()) throw std::logic_error("exactNumberText: cannot format a number");
  std::string s(buf, r.ptr);
  // A whole number keeps a decimal point so that YAML readers see a real number.
  if (std::isfinite(v) && s.find_first_of(".en") == std::string::npos) s += ".0";
  return s;
}

double exactDegrees(double rad) {
  // Of the values a few ulps either side of rad / kDeg that convert back exactly, the one with
  // the shortest text (30 rather than 29.999999999999996).
  const double d0 = rad / kDeg;
  double best = d0;
  size_t best_len = SIZE_MAX;
  double up = d0, down = d0;
  for (int i = 0; i < 8; ++i) {
    for (const double d : {up, down}) {
      const size_t len = exactNumberText(d).size();
      if (d * kDeg == rad && len < best_len) best = d, best_len = len;
    }
    up = std::nextafter(up, INFINITY);
    down = std::nextafter(down, -INFINITY);
  }
  return best;
}

YAML::Node MapWriter::numbers(const double* v, size_t n) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (size_t i = 0; i < n; ++i) list.push_back(exactNumberText(v[i]));
  list.SetStyle(YAML::EmitterStyle::Flow);
  return list;
}

std::string yamlText(const YAML::Node& root) {
  YAML::Emitter e;
  e << root;
  return std::string(e.c_str()) + "\n";
}

}  // namespace msb
