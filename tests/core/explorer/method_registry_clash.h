// A minimal method for the clash test (registered twice under one name on purpose).
#pragma once

#include "core/explorer/method_registry.h"

namespace msb {

struct ClashConfig {
  template <class Self, class V>
  static void fields(Self&, V&) {}
  void validate(ConfigChecker&) const {}
};

// A config with a key that every method: section already has (method.type).
struct TypedConfig {
  std::string type = "mine";
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("type", s.type);
  }
  void validate(ConfigChecker&) const {}
};

class ClashExplorer final : public Explorer {
 public:
  ClashExplorer(const ClashConfig&, const ExplorerContext&) {}
  ClashExplorer(const TypedConfig&, const ExplorerContext&) {}
  void observe(const SlamPointsFrame&) override {}
  std::optional<PathCommand> plan(const VehicleState&) override { return std::nullopt; }
  ExplorerSnapshot snapshot() const override { return {}; }
  std::map<std::string, double> counters() const override { return {}; }
};

}  // namespace msb
