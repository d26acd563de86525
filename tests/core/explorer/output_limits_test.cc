// The contract on a method's output (core/explorer/output_limits.h): each limit names what broke it.
#include "core/explorer/output_limits.h"

#include <gtest/gtest.h>

#include <cmath>

namespace msb {
namespace {

TEST(FreeSpaceLimits, NamesTheBadElement) {
  const Aabb box{Vec3(0, 0, 0), Vec3(10, 10, 5)};
  FreeSpaceElement ok;
  ok.radius = 2.0;
  EXPECT_FALSE(freeSpaceProblem({ok}, box));
  FreeSpaceElement nan = ok;
  nan.centre.x() = std::nan("");
  EXPECT_NE(freeSpaceProblem({ok, nan}, box)->find("element 1"), std::string::npos);
  FreeSpaceElement huge = ok;
  huge.radius = 1e9;
  EXPECT_NE(freeSpaceProblem({huge}, box)->find("radius"), std::string::npos);
  FreeSpaceElement negative = ok;
  negative.radius = -1;
  EXPECT_TRUE(freeSpaceProblem({negative}, box));
  FreeSpaceElement far = ok;
  far.centre = Vec3(1e300, 0, 0);
  EXPECT_NE(freeSpaceProblem({far}, box)->find("outside the exploration box"), std::string::npos);
  FreeSpaceElement inf = ok;
  inf.radius = INFINITY;
  EXPECT_TRUE(freeSpaceProblem({inf}, box));
}

TEST(WaypointLimits, NamesWhatIsWrong) {
  const Vec3 start(1, 2, 0);
  EXPECT_FALSE(waypointProblem({Vec3(500, 2, 3), 0.5}, start));
  EXPECT_EQ(*waypointProblem({Vec3(std::nan(""), 0, 0), std::nullopt}, start), "is not finite");
  EXPECT_EQ(*waypointProblem({Vec3(0, 0, 0), INFINITY}, start), "is not finite");
  const auto far = waypointProblem({Vec3(1 + kMaxWaypointDistanceM + 1, 2, 0), std::nullopt}, start);
  ASSERT_TRUE(far);
  EXPECT_NE(far->find("from the start (the limit is 1000 m)"), std::string::npos) << *far;
}

}  // namespace
}  // namespace msb
