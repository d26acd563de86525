// The paper's coverage metric (docs/architecture.md §10): the xy plane is cut into 2.5 m columns; column
// (i, j) is explored once its node (2.5 i, 2.5 j) lies inside the xy footprint of a free-space
// element (a sphere's disk of radius r at any height, or a free voxel's square). Cumulative:
// a column is never un-marked. A = 6.25 m² × explored columns.
#pragma once

#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "core/common/types.h"
#include "core/explorer/snapshot.h"

namespace msb {

/// Column index (i, j): the column whose node is (cell·i, cell·j).
using ColumnIndex = std::pair<int64_t, int64_t>;

/// A free-space element placed in the true frame (the metric's view of it): a disk, or a square
/// turned by the estimate → truth correction's yaw.
struct PlacedElement {
  uint64_t key = 0;  ///< identifies the element and its placement (id, geometry, correction)
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;  ///< the disk's radius or the square's half side
  FreeSpaceElement::Footprint footprint = FreeSpaceElement::Footprint::kDisk;
  double yaw_rad = 0.0;  ///< the square's turn (squares only)
};

/// The columns (cell `cell_m`) whose node lies in the element's xy footprint, in index order.
std::vector<ColumnIndex> columnsUnder(const PlacedElement& e, double cell_m);

/// Cumulative set of explored columns.
class ColumnCoverage {
 public:
  /// `cell_m`: column size (2.5 m in the paper).
  explicit ColumnCoverage(double cell_m = 2.5);

  /// Marks every column whose node lies inside the disk |xy − c| ≤ r; returns how many were new.
  int markDisk(const Vec2& centre, double radius_m);
  /// Marks every column whose node lies inside the axis-aligned square |xy − c|∞ ≤ half_size.
  int markSquare(const Vec2& centre, double half_size_m);
  /// Marks one column; returns 1 if it was new.
  int markColumn(const ColumnIndex& c) { return int(columns_.insert(c).second); }
  /// Marks every column whose node lies in the placed element's footprint (columnsUnder).
  int markPlaced(const PlacedElement& e);
  /// Marks the footprint of every element (the only way a method's free space becomes columns:
  /// the methods expose geometry, the metric scores it). Returns how many columns were new.
  int markFreeSpace(const std::vector<FreeSpaceElement>& elements);

  /// Explored columns (ordered, for drawing and hashing).
  const std::set<ColumnIndex>& columns() const { return columns_; }
  /// Number of explored columns.
  size_t count() const { return columns_.size(); }
  /// Explored area in m² (unbounded, as in the paper).
  double areaM2() const { return double(columns_.size()) * cell_ * cell_; }
  /// Explored columns whose node lies in the xy rectangle [lo, hi].
  size_t countInside(const Vec2& lo, const Vec2& hi) const;
  /// Column size.
  double cellM() const { return cell_; }
  /// The node of a column.
  Vec2 node(const ColumnIndex& c) const { return Vec2(cell_ * double(c.first), cell_ * double(c.second)); }

 private:
  double cell_;
  std::set<ColumnIndex> columns_;
};

}  // namespace msb
