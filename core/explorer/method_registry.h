// Methods that register themselves from their own folder (docs/architecture.md, "How to add an
// exploration method"): one line in the method's own source,
//
//   const MethodRegistrar kRegistered = registerMethod<HoverTurnExplorer, HoverTurnConfig>(
//       {"hover_turn", "example method: take off, turn once, descend", {"turn_steps", "points_seen"}});
//
// adds it to the methods msbench knows — `method.type: hover_turn` in a scenario, its keys read,
// written and validated through its config's key table (core/common/config_fields.h), its
// explorer built by the loop, `msbench methods` listing it — with no edit outside the folder.
// This header depends on core/common alone (the camera is only declared): a method's folder
// stays free of the YAML layer, which visits the table through the virtual KeyVisitor.
#pragma once

#include <any>
#include <array>
#include <functional>
#include <memory>
#include <source_location>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/common/config_fields.h"
#include "core/explorer/explorer.h"

namespace msb {

class FisheyeCamera;

/// A key table visited through virtual calls (the YAML layer implements it): the same calls as
/// a table's template visitor, for the types a table may hold.
class KeyVisitor {
 public:
  virtual ~KeyVisitor() = default;
  virtual void key(const char* name, double& v, const Limits& l) = 0;
  virtual void key(const char* name, int& v, const Limits& l) = 0;
  virtual void key(const char* name, uint64_t& v, const Limits& l) = 0;
  virtual void key(const char* name, Vec2& v, const Limits& l) = 0;
  virtual void key(const char* name, Vec3& v, const Limits& l) = 0;
  virtual void key(const char* name, std::array<double, 3>& v, const Limits& l) = 0;
  virtual void key(const char* name, std::array<double, 4>& v, const Limits& l) = 0;
  virtual void key(const char* name, bool& v) = 0;
  virtual void key(const char* name, std::string& v) = 0;
  virtual void key(const char* name, std::string& v, const Choices& c) = 0;
  /// A nested group: `body` visits its keys with the visitor of the group.
  virtual void group(const char* name, const std::function<void(KeyVisitor&)>& body) = 0;
  virtual void moved(const char* name, const char* where) = 0;
};

/// The template visitor a table's fields() is called with, forwarding to a KeyVisitor.
class ForwardKeys {
 public:
  explicit ForwardKeys(KeyVisitor& v) : v_(v) {}
  template <class T, class... Rule>
  void key(const char* name, T& value, const Rule&... rule) {
    v_.key(name, value, rule...);
  }
  template <class Sub>
  void group(const char* name, Sub& sub) {
    v_.group(name, [&sub](KeyVisitor& inner) {
      ForwardKeys f(inner);
      Sub::fields(sub, f);
    });
  }
  void moved(const char* name, const char* where) { v_.moved(name, where); }

 private:
  KeyVisitor& v_;
};

/// What a method says about itself when it registers.
struct MethodInfo {
  std::string type;                            ///< `method.type` (letters, digits and '_', not empty)
  std::string summary;                         ///< one line, for `msbench methods` and errors
  std::vector<std::string> progress_counters;  ///< the counters the progress line shows, in order
};

/// A registered method: its info and its config and explorer, type-erased.
struct MethodRegistration {
  MethodInfo info;
  std::string source_file;                   ///< the source file that registered it (for errors naming both of a clash)
  std::function<std::any()> default_config;  ///< the config with its defaults
  std::function<void(std::any& config, KeyVisitor& keys)> keys;            ///< visits the config's key table
  std::function<void(const std::any& config, ConfigChecker& c)> validate;  ///< the config's validate()
  /// Builds the explorer from a (validated) config.
  std::function<std::unique_ptr<Explorer>(const std::any& config, const FisheyeCamera& camera,
                                          const ExplorerContext& context)>
      make;
};

/// A registration that cannot be used: two methods under one type name, an empty or malformed
/// name. The message names the source files. Bad input of the build, not a crash: commands that
/// need the methods exit 2 with it; the others (`--help`) run.
class MethodRegistryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Every method registered so far, sorted by type (static registrars run before main()). Throws
/// MethodRegistryError naming the files if a registration clashed or was malformed.
std::vector<MethodRegistration> registeredMethods();

/// Adds a registration; registerMethod() calls it. Never throws (it runs before main()): a clash
/// is kept and reported by registeredMethods().
void addMethodRegistration(MethodRegistration r) noexcept;

/// The proof that a method registered (keep it as a namespace-scope constant of the method).
struct MethodRegistrar {
  std::string type;
};

/// Registers `ExplorerT` with its `Config` (which has a key table and validate()); the explorer
/// is constructed from (config, camera, context) or (config, context).
template <class ExplorerT, class Config>
MethodRegistrar registerMethod(MethodInfo info, std::source_location where = std::source_location::current()) {
  MethodRegistration r;
  r.info = info;
  r.source_file = where.file_name();
  r.default_config = [] { return std::any(Config{}); };
  r.keys = [](std::any& config, KeyVisitor& v) {
    ForwardKeys f(v);
    Config::fields(std::any_cast<Config&>(config), f);
  };
  r.validate = [](const std::any& config, ConfigChecker& c) { std::any_cast<const Config&>(config).validate(c); };
  r.make = [](const std::any& config, const FisheyeCamera& camera,
              const ExplorerContext& context) -> std::unique_ptr<Explorer> {
    const Config& c = std::any_cast<const Config&>(config);
    if constexpr (std::is_constructible_v<ExplorerT, const Config&, const FisheyeCamera&, const ExplorerContext&>)
      return std::make_unique<ExplorerT>(c, camera, context);
    else
      return std::make_unique<ExplorerT>(c, context);
  };
  addMethodRegistration(std::move(r));
  return {info.type};
}

}  // namespace msb
