// SPDX-License-Identifier: Apache-2.0
#pragma once
// Checks shared by the Params::validate() of the components: each appends
// "field: reason" to the list when the value is out of range, so a validate()
// collects every violation instead of stopping at the first (cFS table
// validation). The predicates are written so that NaN fails them.

#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace flatsat {

/// [-] how far |v| may stray from 1 for v to count as a unit vector.
inline constexpr double kUnitTolerance = 1e-6;

/// Finite and > 0.
inline bool isPositive(double value) { return value > 0.0 && std::isfinite(value); }

/// Finite and >= 0.
inline bool isNonNegative(double value) { return value >= 0.0 && std::isfinite(value); }

/// Every coefficient finite and |v| within kUnitTolerance of 1.
template <class Derived>
bool isUnit(const Eigen::MatrixBase<Derived>& v) {
  return v.allFinite() && std::abs(v.norm() - 1.0) <= kUnitTolerance;
}

/// Appends "field: reason" unless ok.
inline void require(std::vector<std::string>& errors, bool ok, std::string_view field,
                    std::string_view reason) {
  if (!ok) {
    std::string error(field);
    error += ": ";
    error += reason;
    errors.push_back(std::move(error));
  }
}

/// Appends the violations another validate() found (e.g. of a nested struct).
inline void append(std::vector<std::string>& errors, std::vector<std::string> more) {
  errors.insert(errors.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
}

/// "field: must be finite and > 0".
inline void requirePositive(std::vector<std::string>& errors, std::string_view field, double value) {
  require(errors, isPositive(value), field, "must be finite and > 0");
}

/// "field: must be finite and >= 0".
inline void requireNonNegative(std::vector<std::string>& errors, std::string_view field, double value) {
  require(errors, isNonNegative(value), field, "must be finite and >= 0");
}

/// "field: every <element> must be finite and > 0", e.g. element "axis" or "coil".
template <class Derived>
void requireAllPositive(std::vector<std::string>& errors, std::string_view field,
                        const Eigen::MatrixBase<Derived>& v, std::string_view element) {
  const bool ok = v.allFinite() && v.minCoeff() > 0.0;
  require(errors, ok, field, "every " + std::string(element) + " must be finite and > 0");
}

/// "field: must be finite" (every coefficient).
template <class Derived>
void requireFinite(std::vector<std::string>& errors, std::string_view field,
                   const Eigen::MatrixBase<Derived>& v) {
  require(errors, v.allFinite(), field, "must be finite");
}

/// "field: must be a unit vector" (see kUnitTolerance).
template <class Derived>
void requireUnit(std::vector<std::string>& errors, std::string_view field,
                 const Eigen::MatrixBase<Derived>& v) {
  require(errors, isUnit(v), field, "must be a unit vector");
}

/// "field: must be in lo..hi" (both ends included).
inline void requireInRange(std::vector<std::string>& errors, std::string_view field, int value, int lo,
                           int hi) {
  require(errors, value >= lo && value <= hi, field,
          "must be in " + std::to_string(lo) + ".." + std::to_string(hi));
}

/// p itself when p.validate() finds nothing; else throws std::invalid_argument
/// "<name>: field: reason; field: reason; …" (for constructors' initialiser lists).
template <class Params>
const Params& validated(const Params& p, std::string_view name) {
  const std::vector<std::string> errors = p.validate();
  if (errors.empty()) return p;
  std::string message(name);
  message += ":";
  for (const auto& e : errors) message += " " + e + ";";
  throw std::invalid_argument(message);
}

}  // namespace flatsat
