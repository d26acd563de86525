// The 2.5 m column metric on hand-built disks and squares: exact node counts.
#include <gtest/gtest.h>

#include <cmath>

#include "core/eval/column_coverage.h"

namespace msb {
namespace {

TEST(ColumnCoverage, DiskCountsNodesInsideExactly) {
  ColumnCoverage c;
  EXPECT_EQ(c.markDisk({0, 0}, 2.49), 1);  // only the node at the centre
  EXPECT_EQ(c.markDisk({0, 0}, 2.5), 4);   // + the 4 axis neighbours (boundary counts)
  EXPECT_EQ(c.count(), 5u);
  EXPECT_EQ(c.markDisk({0, 0}, 3.54), 4);  // + the 4 diagonal nodes at 3.5355 m
  EXPECT_EQ(c.count(), 9u);
  EXPECT_DOUBLE_EQ(c.areaM2(), 9 * 6.25);
  ColumnCoverage d;
  EXPECT_EQ(d.markDisk({1.25, 1.25}, 1.76), 0);  // node distance is 1.7678 m
  EXPECT_EQ(d.markDisk({1.25, 1.25}, 1.77), 4);
  EXPECT_EQ(d.markDisk({-10.0, 7.5}, 5.0), 13);  // radius 2 cells: i² + j² ≤ 4 → 13 nodes
}

TEST(ColumnCoverage, IsCumulativeAndBoxCounting) {
  ColumnCoverage c;
  c.markDisk({0, 0}, 10.0);
  const size_t n = c.count();
  EXPECT_EQ(c.markDisk({0, 0}, 3.0), 0);  // a shrunken sphere never un-marks columns
  EXPECT_EQ(c.count(), n);
  // Radius-4-cell disk: lattice points with i² + j² ≤ 16.
  int expect = 0;
  for (int i = -4; i <= 4; ++i)
    for (int j = -4; j <= 4; ++j) expect += i * i + j * j <= 16;
  EXPECT_EQ(int(n), expect);
  EXPECT_EQ(c.countInside({0, 0}, {10, 10}), 17u);  // quadrant incl. axes: i, j ≥ 0, i² + j² ≤ 16
  ColumnCoverage s;
  EXPECT_EQ(s.markSquare({0, 0}, 2.5), 9);
  EXPECT_EQ(s.markSquare({0, 0}, 2.4), 0);
  EXPECT_EQ(s.countInside({-1, -1}, {1, 1}), 1u);
  EXPECT_THROW(ColumnCoverage(0.0), std::invalid_argument);
}

TEST(ColumnCoverage, FreeSpaceIsScoredByEachElementsFootprint) {
  // The metric reads a method's free space as geometry: a disk of radius 2.5 m covers the node
  // (0, 0) and its four neighbours; a square of half side 2.5 m also its four diagonal ones.
  using F = FreeSpaceElement::Footprint;
  ColumnCoverage disks, squares;
  EXPECT_EQ(disks.markFreeSpace({{1, Vec3(0, 0, 3), 2.5, F::kDisk}}), 5);
  EXPECT_EQ(squares.markFreeSpace({{1, Vec3(0, 0, 3), 2.5, F::kSquare}}), 9);
  EXPECT_EQ(squares.markFreeSpace({{2, Vec3(0, 0, 3), 2.5, F::kDisk}, {3, Vec3(10, 0, 1), 0.1, F::kSquare}}), 1);
}

}  // namespace
}  // namespace msb
