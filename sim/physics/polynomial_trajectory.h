// A piecewise polynomial trajectory in x, y, z and heading, as the ETH polynomial optimisation
// inside the MRS trajectory generator builds it (eth_trajectory_generation with N = 10): each
// segment a polynomial of degree 9 in every dimension, continuous up to the 4th derivative (snap)
// at inner vertices, minimising the integral of the squared acceleration (the generator's
// `derivative_to_optimize: 0`) for given segment times. The solution is the unconstrained one of
// Richter et al.: the free endpoint derivatives of every vertex solve a linear system.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

namespace msb {

/// x, y, z and heading.
using Vec4 = Eigen::Matrix<double, 4, 1>;

/// What a vertex fixes: derivatives 0 (position) to 4 (snap), each optional.
struct PolyVertex {
  std::array<std::optional<Vec4>, 5> fixed;  ///< the fixed derivative values (time units: seconds)
};

/// Piecewise polynomial (degree 9, 4 dimensions) with minimum squared acceleration.
class PolynomialTrajectory {
 public:
  /// Number of endpoint derivatives per vertex the polynomial is continuous in (0…4).
  static constexpr int kDerivatives = 5;
  /// Coefficients per segment and dimension.
  static constexpr int kCoefficients = 10;

  /// Solves for the vertices and segment times (`times.size() == vertices.size() - 1`, each > 0).
  /// Returns false if the system is singular (too few fixed values).
  bool solve(const std::vector<PolyVertex>& vertices, const std::vector<double>& times);
  /// Stretches segment `seg` in time by `factor` keeping its shape (the generator's
  /// scalePolynomialInTime): derivative k scales by factor^-k. Continuity across vertices is then
  /// broken until the next solve().
  void stretchSegment(size_t seg, double factor);

  /// The segment times.
  const std::vector<double>& times() const { return times_; }
  /// Total duration.
  double duration() const;
  /// The cost: the integral of the squared acceleration over every dimension.
  double cost() const { return cost_; }
  /// Derivative `order` (0…4) of the trajectory at time t (clamped to [0, duration]).
  Vec4 at(double t, int order) const;
  /// Derivative `order` of segment `seg` at its local time t in [0, times()[seg]].
  Vec4 segmentAt(size_t seg, double t, int order) const;

 private:
  std::vector<double> times_;
  // Per segment: coefficients in normalised time τ = t/T (rows: power, columns: dimension).
  std::vector<Eigen::Matrix<double, kCoefficients, 4>> coefficients_;
  double cost_ = 0.0;
};

}  // namespace msb
