// How runs name their method (summary line, video caption): methodLabel() of tools/engine/methods.h.
#include "tools/engine/methods.h"

#include <gtest/gtest.h>

#include "core/methods/monospheres/planner/monospheres_explorer.h"

namespace msb {
namespace {

// MonoSpheres with `c`, made from its registration as a scenario's method is.
MethodChoice monospheres(const MonoSpheresConfig& c) {
  const MethodRegistration* reg = findRegistration("monospheres");
  if (!reg) throw std::logic_error("monospheres is not registered");
  return registeredMethodChoice(*reg, c);
}

TEST(MethodLabel, NamesTheTypeTheSwitchesOffAndThePublishedDefectsOn) {
  MonoSpheresConfig c;
  EXPECT_EQ(methodLabel(monospheres(c)), "monospheres");
  c.map.ovde = false;
  c.planner.goals.fff = false;
  EXPECT_EQ(methodLabel(monospheres(c)), "monospheres -fff -ovde");
  c.reference_code.path_resend_8s = true;
  EXPECT_EQ(methodLabel(monospheres(c)), "monospheres -fff -ovde +path_resend_8s");
  c.reference_code = ReferenceCodeConfig::published();
  EXPECT_EQ(methodLabel(monospheres(c)), "monospheres -fff -ovde +published");
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

TEST(Methods, TheDefaultMethodIsANameLookedUpInTheRegistry) {
  const MethodChoice m = defaultMethod();
  EXPECT_EQ(m.type, kDefaultMethodType);
  EXPECT_NE(std::any_cast<MonoSpheresConfig>(&m.config), nullptr);
  EXPECT_TRUE(takesGoalChooser(m));
  ASSERT_EQ(m.hooks.size(), 1u);
  EXPECT_EQ(m.hooks[0].name, "viewpoint_chooser");
  EXPECT_EQ(findRegistration("no_such_method"), nullptr);
  ASSERT_NE(findRegistration("grid_random"), nullptr);
  EXPECT_EQ(registeredMethodChoice(*findRegistration("grid_random"), findRegistration("grid_random")->default_config())
                .octree_resolution_m,
            0.5);
  // Methods written in Python are a registration like the others; they offer no hook.
  ASSERT_NE(findRegistration("python"), nullptr);
  EXPECT_FALSE(takesGoalChooser(
      registeredMethodChoice(*findRegistration("python"), findRegistration("python")->default_config())));
}

}  // namespace
}  // namespace msb
