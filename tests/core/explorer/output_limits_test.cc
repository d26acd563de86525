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

TEST(FreeSpaceLimits, AFloodOfLargeElementsIsRefusedByItsTotalFootprint) {
  // 1000 disks of 250 m (the flood that cost 27.9 s of metric time per simulated second) pass
  // every per-element limit; their footprint, 2·10⁸ m², does not. Fifteen disks of 145 m
  // (0.99·10⁶ m²) are within it; a sixteenth square of 50 m half side (10⁴ m²) is not.
  const Aabb box{Vec3(0, 0, 0), Vec3(100, 100, 7)};
  FreeSpaceElement disk;
  disk.radius = 250.0;
  const auto flood = freeSpaceProblem(std::vector<FreeSpaceElement>(1000, disk), box);
  ASSERT_TRUE(flood);
  EXPECT_NE(flood->find("total footprint passes 1000000 m² at free-space element 5 "), std::string::npos) << *flood;
  disk.radius = 145.0;
  std::vector<FreeSpaceElement> fifteen(15, disk);
  EXPECT_FALSE(freeSpaceProblem(fifteen, box));
  FreeSpaceElement square;
  square.radius = 50.0;
  square.footprint = FreeSpaceElement::Footprint::kSquare;
  fifteen.push_back(square);
  EXPECT_TRUE(freeSpaceProblem(fifteen, box));
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
