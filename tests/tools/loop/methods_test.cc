// How runs name their method (summary line, video caption): methodLabel() of tools/loop/methods.h.
#include "tools/loop/methods.h"

#include <gtest/gtest.h>

namespace msb {
namespace {

TEST(MethodLabel, NamesTheTypeTheSwitchesOffAndThePublishedDefectsOn) {
  MonoSpheresConfig c;
  EXPECT_EQ(methodLabel(monospheresMethod(c)), "monospheres");
  c.map.ovde = false;
  c.planner.fff = false;
  EXPECT_EQ(methodLabel(monospheresMethod(c)), "monospheres -fff -ovde");
  c.reference_code.path_resend_8s = true;
  EXPECT_EQ(methodLabel(monospheresMethod(c)), "monospheres -fff -ovde +path_resend_8s");
  c.reference_code = ReferenceCodeConfig::published();
  EXPECT_EQ(methodLabel(monospheresMethod(c)), "monospheres -fff -ovde +published");
}

}  // namespace
}  // namespace msb
