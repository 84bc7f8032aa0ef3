// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <array>
#include <string>

namespace flatsat::sim {

/// Schmidt semi-normalised Gauss coefficients of an internal field at one time.
struct GaussCoefficients {
  static constexpr int kMaxDegree = 13;
  using Table = std::array<std::array<double, kMaxDegree + 1>, kMaxDegree + 1>;  // [n][m], m ≤ n

  int degree = 1;             // [-] N, highest degree used, 1..kMaxDegree
  double decimal_year = 0.0;  // [yr] time the coefficients apply at
  Table g_nT{};               // [nT] g_n^m
  Table h_nT{};               // [nT] h_n^m (h_n^0 unused)
  Table g_dot_nT_yr{};        // [nT/yr] secular variation of g_n^m at decimal_year
  Table h_dot_nT_yr{};        // [nT/yr] secular variation of h_n^m
};

/// IGRF-14 at decimal_year [yr] from the IAGA coefficient table (rows "g|h n m",
/// one column per 5-year epoch, then the secular variation [nT/yr] for the five
/// years after the last epoch): linear between epochs, last epoch + (t − last)·SV
/// after it (the IGRF convention; Alken et al. 2021, Earth Planets Space 73:49). The degree is the
/// highest with a non-zero term at that time (10 before 1995, 13 from 2000).
/// @throws std::runtime_error naming the file, the line and the reason when the
///         file is missing or malformed or the year is outside the table.
GaussCoefficients igrf14Coefficients(const std::string& igrf_coeff_file, double decimal_year);

/// WMM2025 at decimal_year [yr] from its .COF file (header "epoch name date", rows
/// "n m g h ġ ḣ", closed by a line of 9s): g(t) = g(t₀) + (t − t₀)·ġ for
/// t₀ ≤ t ≤ t₀ + 5.
/// @throws std::runtime_error naming the file, the line and the reason.
GaussCoefficients wmm2025Coefficients(const std::string& wmm_cof_file, double decimal_year);

}  // namespace flatsat::sim
