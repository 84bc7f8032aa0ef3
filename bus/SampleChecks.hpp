// SPDX-License-Identifier: Apache-2.0
#pragma once
// What a consumer checks of every sample it takes from the bus (architecture,
// "Trust on the bus"): hardware and foreign code join the bus by design, so
// a sample counts only when every value is finite and inside the physical
// range of its topic's contract. A refused sample is taken as missing: the
// form a dropout of its producer has (a reading with valid = false, an
// estimate that is not valid, a zero command), so a lockstep step still
// completes and nothing downstream ever sees the bad value.
//
// The ranges are physical bounds, wide of any spacecraft this rig flies, not
// a sensor's specified range: a value past them is a unit error, a broken
// device or a hostile writer, never a measurement.
#include <cstdint>

namespace flatsat::bus {

/// [T] |B| bound per axis: Earth's field is below 7e-5 T at the surface.
inline constexpr double kMaxFieldT = 1e-3;
/// [rad/s] body rate bound per axis (a tumble of ~480 deg/s).
inline constexpr double kMaxBodyRateRadS = 50.0;
/// [rad/s] wheel speed bound (~19,000 rpm).
inline constexpr double kMaxWheelSpeedRadS = 2000.0;
/// [-] how far a unit vector or quaternion that is valid may stray from norm 1.
inline constexpr double kUnitNormTolerance = 1e-2;
/// [A m^2] torquer dipole bound per axis in a coil request or window.
inline constexpr double kMaxDipoleAm2 = 1e4;
/// [s] bound on a coil window's phases and a thruster's on-time.
inline constexpr double kMaxDurationS = 1e5;
/// [-] a coarse Sun sensor cell's output bound (1: the Sun at normal incidence at 1 AU).
inline constexpr double kMaxCellOutput = 10.0;

/// Why a sample breaks its topic's contract: the field and the reason;
/// both null when it keeps it. Static strings: checking allocates nothing.
struct Breach {
  const char* field = nullptr;
  const char* reason = nullptr;
  explicit operator bool() const { return field != nullptr; }
};

/// The breach of `sample`, if any: a value that is not finite, or one
/// outside its topic's range. Defined for every registry topic's type.
template <class Sample>
Breach breachOf(const Sample& sample);

/// Turns a refused sample into its topic's missing form, header kept (see
/// the top of this file). False where the topic has none (the truth, the
/// protocol's grants): the sample is then dropped, and a lockstep consumer
/// waits for the producer's resend or fails naming the topic.
template <class Sample>
bool takeAsMissing(Sample& sample);

}  // namespace flatsat::bus
