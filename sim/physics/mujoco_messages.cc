#include "sim/physics/mujoco_messages.h"

#include <cstdio>
#include <set>

namespace msb {

namespace {

// Never returns: MuJoCo must not continue after an error (unwinding through its C frames is
// safe: the library is built with unwind tables).
void throwMujocoError(const char* msg) { throw MujocoError(msg ? msg : "unknown MuJoCo error"); }

// Each distinct warning text once per process (the counters say how often).
void printWarningOnce(const char* msg) {
  static std::set<std::string> printed;
  const std::string text = msg ? msg : "?";
  if (printed.insert(text).second) std::fprintf(stderr, "msbench: MuJoCo warning: %s\n", text.c_str());
}

}  // namespace

void installMujocoHandlers() {
  mju_user_error = throwMujocoError;
  mju_user_warning = printWarningOnce;
}

std::map<std::string, int> mujocoWarningCounts(const mjData* d) {
  static constexpr const char* kNames[mjNWARNING] = {"inertia",  "contact_full", "constraint_full", "visual_geom_full",
                                                     "bad_qpos", "bad_qvel",     "bad_qacc",        "bad_ctrl"};
  std::map<std::string, int> out;
  for (int i = 0; i < mjNWARNING; ++i)
    if (d->warning[i].number > 0) out[kNames[i]] = d->warning[i].number;
  return out;
}

}  // namespace msb
