#include "sim/physics/polynomial_trajectory.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace msb {
namespace {

constexpr int kD = PolynomialTrajectory::kDerivatives;
constexpr int kN = PolynomialTrajectory::kCoefficients;
using Mat10 = Eigen::Matrix<double, kN, kN>;

// j! / (j - k)!: the factor of τ^(j-k) in the k-th derivative of τ^j.
double fallingFactorial(int j, int k) {
  double f = 1.0;
  for (int i = 0; i < k; ++i) f *= double(j - i);
  return f;
}

// The map from a segment's endpoint derivatives in τ units (0…4 at τ = 0, then at τ = 1) to
// its coefficients, inverted once.
const Mat10& endpointsToCoefficients() {
  static const Mat10 inv = [] {
    Mat10 a = Mat10::Zero();
    for (int k = 0; k < kD; ++k) {
      a(k, k) = fallingFactorial(k, k);
      for (int j = k; j < kN; ++j) a(kD + k, j) = fallingFactorial(j, k);
    }
    return Mat10(a.fullPivLu().inverse());
  }();
  return inv;
}

// The cost of a segment in τ units as a form over its endpoint derivatives: A⁻ᵀ Q A⁻¹, with Q the
// integral over [0, 1] of the squared second derivative.
const Mat10& endpointCost() {
  static const Mat10 r = [] {
    Mat10 q = Mat10::Zero();
    for (int j = 2; j < kN; ++j)
      for (int k = 2; k < kN; ++k) q(j, k) = fallingFactorial(j, 2) * fallingFactorial(k, 2) / double(j + k - 3);
    const Mat10& inv = endpointsToCoefficients();
    return Mat10(inv.transpose() * q * inv);
  }();
  return r;
}

// diag(T^k) for the two endpoints: t-unit derivatives to τ-unit ones.
Eigen::Matrix<double, kN, 1> timeScale(double t) {
  Eigen::Matrix<double, kN, 1> s;
  for (int k = 0; k < kD; ++k) s(k) = s(kD + k) = std::pow(t, k);
  return s;
}

}  // namespace

bool PolynomialTrajectory::solve(const std::vector<PolyVertex>& vertices, const std::vector<double>& times) {
  const size_t m = times.size();
  if (vertices.size() != m + 1 || m == 0) return false;
  times_ = times;
  const int n = int(kD * vertices.size());

  // The global cost form over every vertex derivative (banded: segments couple neighbours).
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(n, n);
  for (size_t s = 0; s < m; ++s) {
    const auto sc = timeScale(times[s]);
    const Mat10 hs = std::pow(times[s], -3.0) * (sc.asDiagonal() * endpointCost() * sc.asDiagonal());
    h.block<kN, kN>(int(kD * s), int(kD * s)) += hs;
  }

  // Fixed and free derivatives; the free ones minimise the cost given the fixed.
  std::vector<int> fixed_idx, free_idx;
  for (size_t v = 0; v < vertices.size(); ++v)
    for (int k = 0; k < kD; ++k) (vertices[v].fixed[k] ? fixed_idx : free_idx).push_back(int(kD * v) + k);
  Eigen::MatrixXd d(n, 4);
  for (int i : fixed_idx) d.row(i) = vertices[size_t(i / kD)].fixed[size_t(i % kD)]->transpose();
  if (!free_idx.empty()) {
    const int nf = int(free_idx.size()), nx = int(fixed_idx.size());
    Eigen::MatrixXd hpp(nf, nf), hpf(nf, nx), df(nx, 4);
    for (int a = 0; a < nf; ++a) {
      for (int b = 0; b < nf; ++b) hpp(a, b) = h(free_idx[a], free_idx[b]);
      for (int b = 0; b < nx; ++b) hpf(a, b) = h(free_idx[a], fixed_idx[b]);
    }
    for (int b = 0; b < nx; ++b) df.row(b) = d.row(fixed_idx[b]);
    // Jacobi-scaled (segment times from 0.01 s to minutes span many orders of magnitude), then
    // positive definite: every free value is pinned by the cost (constant and linear terms cost
    // nothing, so a vertex without a fixed position leaves the system singular).
    const Eigen::VectorXd hd = hpp.diagonal();
    if (hd.minCoeff() <= 0.0) return false;
    const Eigen::VectorXd sc = hd.cwiseSqrt().cwiseInverse();
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(sc.asDiagonal() * hpp * sc.asDiagonal());
    const Eigen::VectorXd diag = ldlt.vectorD();
    if (ldlt.info() != Eigen::Success || diag.minCoeff() <= 1e-12 * diag.cwiseAbs().maxCoeff()) return false;
    const Eigen::MatrixXd dp = sc.asDiagonal() * ldlt.solve(sc.asDiagonal() * (-hpf * df));
    if (!dp.allFinite()) return false;
    for (int a = 0; a < nf; ++a) d.row(free_idx[a]) = dp.row(a);
  }

  // Coefficients per segment, and the cost.
  coefficients_.resize(m);
  cost_ = 0.0;
  for (size_t s = 0; s < m; ++s) {
    const auto sc = timeScale(times[s]);
    const Eigen::Matrix<double, kN, 4> ends = sc.asDiagonal() * d.block<kN, 4>(int(kD * s), 0);
    coefficients_[s] = endpointsToCoefficients() * ends;
    cost_ += std::pow(times[s], -3.0) * (ends.transpose() * endpointCost() * ends).trace();
  }
  return std::isfinite(cost_);
}

void PolynomialTrajectory::stretchSegment(size_t seg, double factor) {
  // In τ units the shape is unchanged; only the duration grows.
  times_[seg] *= factor;
}

double PolynomialTrajectory::duration() const { return std::accumulate(times_.begin(), times_.end(), 0.0); }

Vec4 PolynomialTrajectory::segmentAt(size_t seg, double t, int order) const {
  const double len = times_[seg];
  const double tau = std::clamp(t / len, 0.0, 1.0);
  Vec4 out = Vec4::Zero();
  // Horner over the differentiated coefficients.
  for (int j = kN - 1; j >= order; --j)
    out = out * tau + fallingFactorial(j, order) * coefficients_[seg].row(j).transpose();
  return out * std::pow(len, -order);
}

Vec4 PolynomialTrajectory::at(double t, int order) const {
  double start = 0.0;
  for (size_t s = 0; s + 1 < times_.size(); ++s) {
    if (t < start + times_[s]) return segmentAt(s, t - start, order);
    start += times_[s];
  }
  return segmentAt(times_.size() - 1, t - start, order);
}

}  // namespace msb
