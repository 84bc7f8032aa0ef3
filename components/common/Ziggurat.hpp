// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace flatsat {

/// Standard normal variates by the ziggurat method: Marsaglia & Tsang, "The
/// Ziggurat Method for Generating Random Variables", J. Stat. Softw. 5(8),
/// 2000, with their 256-layer constants. Exact up to the tables (every
/// layer's area is v to 1e-9), not an approximation of the density: a point
/// uniform in a layer is kept when it lies under exp(−x²/2), and the base
/// layer's overhang is Marsaglia's (1964) tail method.
///
/// Each variate takes one 64-bit draw when it falls inside its layer's
/// rectangle (98.5 % of them): layer from bits 0–7, sign from bit 8 and the
/// abscissa from bits 11–63, disjoint bits, so none of the layer–value
/// correlation of the 32-bit original (Leong, Zhang, Lee, Luk & Villasenor,
/// J. Stat. Softw. 12(7), 2005). std::normal_distribution's polar method
/// took a logarithm, a square root and a division per pair and cost a
/// rig step 1.9k instructions for its fifteen draws (callgrind).
class Ziggurat {
 public:
  static constexpr int kLayers = 256;
  static constexpr double kTailStart = 3.6541528853610088;  // r: where the base layer's tail begins
  static constexpr double kLayerArea = 4.92867323399e-3;    // v: area of every layer

  /// The layers' right edges x[0..256] (x[0] = v / f(r), the base layer's
  /// width with its tail folded in; x[1] = r; x[256] = 0) and f(x) = exp(−x²/2) at them.
  struct Tables {
    std::array<double, kLayers + 1> x;
    std::array<double, kLayers + 1> f;
  };
  static const Tables& tables() {
    static const Tables t = build();
    return t;
  }

  /// One N(0, 1) variate; Engine gives 64 uniform bits a call (std::mt19937_64).
  template <class Engine>
  static double sample(Engine& engine) {
    static_assert(Engine::min() == 0 && Engine::max() == std::numeric_limits<std::uint64_t>::max(),
                  "the ziggurat takes 64 uniform bits a draw");
    const Tables& t = tables();
    for (;;) {
      const std::uint64_t bits = engine();
      const unsigned layer = bits & 0xFFu;
      const double sign = (bits & 0x100u) != 0 ? -1.0 : 1.0;
      const double x = unit(bits) * t.x[layer];
      if (x < t.x[layer + 1]) return sign * x;  // inside the layer's rectangle, under the curve
      if (layer == 0) return sign * tail(engine);
      // Between the rectangle and the curve: a uniform height in the layer decides.
      const double y = t.f[layer] + unit(engine()) * (t.f[layer + 1] - t.f[layer]);
      if (y < std::exp(-0.5 * x * x)) return sign * x;
    }
  }

 private:
  /// [0, 1) from the top 53 bits.
  static double unit(std::uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }
  /// (0, 1], for a logarithm.
  static double openUnit(std::uint64_t bits) { return static_cast<double>((bits >> 11) + 1) * 0x1.0p-53; }

  /// |X| given |X| > r (Marsaglia 1964): x = −ln(u₁)/r and y = −ln(u₂) until 2y ≥ x².
  template <class Engine>
  static double tail(Engine& engine) {
    for (;;) {
      const double x = -std::log(openUnit(engine())) / kTailStart;
      const double y = -std::log(openUnit(engine()));
      if (y + y >= x * x) return kTailStart + x;
    }
  }

  static Tables build() {
    Tables t{};
    const auto f = [](double x) { return std::exp(-0.5 * x * x); };
    // Every layer has area v: x[i] (f(x[i+1]) − f(x[i])) = v, solved upwards from x[1] = r.
    t.x[0] = kLayerArea / f(kTailStart);
    t.x[1] = kTailStart;
    for (int i = 1; i < kLayers - 1; ++i) {
      t.x[i + 1] = std::sqrt(-2.0 * std::log(kLayerArea / t.x[i] + f(t.x[i])));
    }
    t.x[kLayers] = 0.0;
    for (int i = 0; i <= kLayers; ++i) t.f[i] = f(t.x[i]);
    return t;
  }
};

}  // namespace flatsat
