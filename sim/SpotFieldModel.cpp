// SPDX-License-Identifier: Apache-2.0
#include "sim/SpotFieldModel.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "sim/Constants.hpp"
#include "sim/Format.hpp"

namespace flatsat::sim {
namespace {

// Samples per revolution for the Fourier projection: the zonal field along the orbit
// is a trigonometric polynomial of degree ≤ 13 in u, so any K > 13 + 5 keeps degrees
// above 5 from aliasing onto harmonics 0..5 and makes the projection exact.
constexpr int kSamples = 32;

}  // namespace

Eigen::Matrix3d R_NO(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s) {
  const Eigen::Vector3d z = r_N_m.normalized();
  const Eigen::Vector3d y = -r_N_m.cross(v_N_m_s).normalized();
  Eigen::Matrix3d R;
  R << y.cross(z), y, z;
  return R;
}

double argumentOfLatitude_rad(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s) {
  const Eigen::Vector3d normal = r_N_m.cross(v_N_m_s).normalized();
  const Eigen::Vector3d to_node = Eigen::Vector3d::UnitZ().cross(normal);
  const Eigen::Vector3d node = to_node.norm() > 1e-12 ? to_node.normalized() : Eigen::Vector3d::UnitX();
  const double u = std::atan2(normal.dot(node.cross(r_N_m)), node.dot(r_N_m));
  return u < 0.0 ? u + kTwoPi : u;
}

SpotFieldModel::SpotFieldModel(const Harmonics& cos_T, const Harmonics& sin_T, double reference_radius_m)
    : cos_T_(cos_T), sin_T_(sin_T), reference_radius_m_(reference_radius_m) {
  if (!(reference_radius_m > 0.0)) {
    throw std::invalid_argument("SpotFieldModel: reference radius " + formatNumber(reference_radius_m) +
                                " m must be positive");
  }
}

SpotFieldModel SpotFieldModel::firstHarmonic(double b0_T, double reference_radius_m) {
  // An axial dipole with a northward field B0 on the equator at r₀ gives, on a polar
  // orbit where the latitude is u, a northward component B0 cos u (along the motion
  // on the ascending half) and an upward one −2 B0 sin u. X points against the
  // motion and Z up, hence the seed's Bx = −B0 cos u, Bz = −2 B0 sin u.
  Harmonics cos_T{};
  Harmonics sin_T{};
  for (int k = 0; k <= kMaxHarmonic; ++k) cos_T[k] = sin_T[k] = Eigen::Vector3d::Zero();
  cos_T[1] = Eigen::Vector3d(-b0_T, 0.0, 0.0);
  sin_T[1] = Eigen::Vector3d(0.0, 0.0, -2.0 * b0_T);
  return SpotFieldModel(cos_T, sin_T, reference_radius_m);
}

SpotFieldModel SpotFieldModel::zonalHarmonics(const SphericalHarmonicField& field, double orbit_radius_m,
                                              double inclination_rad, const std::vector<int>& harmonics) {
  for (const int k : harmonics) {
    if (k < 0 || k > kMaxHarmonic) {
      throw std::invalid_argument("SpotFieldModel: harmonic " + std::to_string(k) + " is outside 0..5");
    }
  }
  if (!(orbit_radius_m > 0.0)) {
    throw std::invalid_argument("SpotFieldModel: orbit radius " + formatNumber(orbit_radius_m) + " m must be positive");
  }
  // Over a day the Earth turns beneath the orbit, so a model in u alone can at best
  // follow the longitude average of the field: its zonal terms g_n⁰, whose potential
  // is V = a Σ (a/r)^(n+1) g_n⁰ P_n(ẑ·r̂) (Alken et al. 2021, Eq. 1, m = 0; Schmidt
  // and Legendre P_n coincide). On a circular orbit ẑ·r̂ = s = sin i sin u, ẑ·v̂ =
  // sin i cos u, ẑ·ĥ = cos i, and −∇V gives in O (X = −v̂, Y = −ĥ, Z = r̂):
  //   B_X = Σ (a/r)^(n+2) g_n⁰ P_n′(s) sin i cos u
  //   B_Y = Σ (a/r)^(n+2) g_n⁰ P_n′(s) cos i
  //   B_Z = Σ (n+1) (a/r)^(n+2) g_n⁰ P_n(s)
  // With g_1⁰ alone and i = 90° this is the seed's first harmonic (B0 = −g_1⁰ (a/r)³).
  // P_n(s) is an odd or even polynomial of degree n in sin u: odd degrees (g_3⁰, g_5⁰)
  // bring harmonics 3 and 5 of B_X and B_Z, even degrees (g_2⁰, g_4⁰) harmonics 0, 2, 4
  // and, off the pole, the cross-track B_Y.
  const GaussCoefficients& c = field.coefficients();
  const double ratio = field.referenceRadius_m() / orbit_radius_m;
  const double sin_i = std::sin(inclination_rad);
  const double cos_i = std::cos(inclination_rad);
  Harmonics all_cos{};
  Harmonics all_sin{};
  for (int k = 0; k <= kMaxHarmonic; ++k) all_cos[k] = all_sin[k] = Eigen::Vector3d::Zero();
  for (int j = 0; j < kSamples; ++j) {
    const double u = kTwoPi * j / kSamples;
    const double s = sin_i * std::sin(u);
    // Legendre recursions: n P_n = (2n − 1) s P_{n−1} − (n − 1) P_{n−2}; P_n′ = n P_{n−1} + s P_{n−1}′.
    double p_prev = 1.0, p = s, dp = 1.0;
    double radial = ratio * ratio * ratio;
    Eigen::Vector3d b_nT = Eigen::Vector3d::Zero();
    for (int n = 1; n <= c.degree; ++n) {
      if (n > 1) {
        const double p_next = ((2.0 * n - 1.0) * s * p - (n - 1.0) * p_prev) / n;
        const double dp_next = n * p + s * dp;
        p_prev = p;
        p = p_next;
        dp = dp_next;
        radial *= ratio;
      }
      b_nT += radial * c.g_nT[n][0] * Eigen::Vector3d(dp * sin_i * std::cos(u), dp * cos_i, (n + 1.0) * p);
    }
    // Discrete Fourier transform, exact for these band-limited samples.
    for (int k = 0; k <= kMaxHarmonic; ++k) {
      const double weight = (k == 0 ? 1.0 : 2.0) / kSamples * 1e-9;  // and nT → T
      all_cos[k] += weight * std::cos(k * u) * b_nT;
      all_sin[k] += weight * std::sin(k * u) * b_nT;
    }
  }
  Harmonics cos_T{};
  Harmonics sin_T{};
  for (int k = 0; k <= kMaxHarmonic; ++k) cos_T[k] = sin_T[k] = Eigen::Vector3d::Zero();
  for (const int k : harmonics) {
    cos_T[k] = all_cos[k];
    sin_T[k] = all_sin[k];
  }
  return SpotFieldModel(cos_T, sin_T, orbit_radius_m);
}

Eigen::Vector3d SpotFieldModel::b_O_T(double argument_of_latitude_rad, double radius_m) const {
  Eigen::Vector3d b = cos_T_[0];
  for (int k = 1; k <= kMaxHarmonic; ++k) {
    b += std::cos(k * argument_of_latitude_rad) * cos_T_[k] + std::sin(k * argument_of_latitude_rad) * sin_T_[k];
  }
  return std::pow(reference_radius_m_ / radius_m, 3) * b;
}

}  // namespace flatsat::sim
