// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <istream>
#include <string>
#include <vector>

namespace flatsat::sim {

/// One NORAD two-line element set, field by field. The fields keep the units the
/// format defines (degrees, revolutions per day, Earth radii), named in each field:
/// Sgp4 converts them exactly as Vallado's twoline2rv does (Vallado et al. 2006,
/// AIAA 2006-6753), which bit-level agreement with its verification output needs.
/// Columns are 1-based, as in the format's description (Hoots & Roehrich 1980,
/// Spacetrack Report #3; CelesTrak "NORAD Two-Line Element Set Format").
struct Tle {
  int catalog_number = 0;                // [-] line 1 cols 3-7, 0..339999 (Alpha-5 letter decoded)
  char classification = 'U';             // [-] line 1 col 8: U, C or S
  std::string international_designator;  // [-] line 1 cols 10-17, e.g. "98067A"; empty when blank
  int epoch_year = 2000;                 // [yr] line 1 cols 19-20 as four digits: 57..99 → 19xx, 00..56 → 20xx
  double epoch_day = 1.0;                // [d] line 1 cols 21-32: day of the year, 1.0 = 1 January 0 h UTC
  double mean_motion_dot = 0.0;          // [rev/d^2] line 1 cols 34-43: dn/dt / 2 (not used by SGP4)
  double mean_motion_ddot = 0.0;         // [rev/d^3] line 1 cols 45-52: d2n/dt2 / 6 (not used by SGP4)
  double bstar = 0.0;                    // [1/Earth radii] line 1 cols 54-61: SGP4 drag term B*
  int ephemeris_type = 0;                // [-] line 1 col 63, 0..9 (0 when blank)
  int element_set_number = 0;            // [-] line 1 cols 65-68, 0..9999
  double inclination_deg = 0.0;          // [deg] line 2 cols 9-16, [0, 180]
  double raan_deg = 0.0;                 // [deg] line 2 cols 18-25, right ascension of the node, [0, 360)
  double eccentricity = 0.0;             // [-] line 2 cols 27-33, [0, 1)
  double arg_perigee_deg = 0.0;          // [deg] line 2 cols 35-42, [0, 360)
  double mean_anomaly_deg = 0.0;         // [deg] line 2 cols 44-51, [0, 360)
  double mean_motion_rev_day = 15.0;     // [rev/d] line 2 cols 53-63, Kozai mean motion, > 0
  int revolution_number = 0;             // [-] line 2 cols 64-68, 0..99999

  /// Every violation as "field (line L, columns a-b): reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// Whether parseTle checks the modulo-10 checksum in column 69 of each line.
enum class TleChecksum { kVerify, kIgnore };

/// Parses the two lines of an element set by column. Numbers may have leading and
/// trailing blanks inside their columns; a blank international designator, ephemeris
/// type, element number or revolution number is accepted, and blank digits of the
/// assumed-decimal fields (eccentricity, d2n/dt2, B*) read as zeros (Vallado's
/// twoline2rv does so for the first two). Characters after column 69 are ignored
/// (Vallado's verification file keeps start, stop and step times there).
/// @throws std::invalid_argument naming the line, the columns, the field and what is
///         wrong (length, line number, number format, checksum, catalogue numbers that
///         differ, values out of range).
Tle parseTle(const std::string& line1, const std::string& line2, TleChecksum checksum = TleChecksum::kVerify);

/// The lines of one element set in a text.
struct TleLines {
  std::string name;     // title line before line 1 (three-line format, without "0 "), or empty
  std::string line1;    // without trailing blanks or carriage return
  std::string line2;    // without trailing blanks or carriage return
  int line_number = 0;  // [-] 1-based number of line 1 in the text
};

/// Splits a two- or three-line element text into element sets. Blank lines and lines
/// starting with '#' are skipped; a line that is neither a line 1 ("1 ...") nor a
/// line 2 ("2 ...") names the set that follows. Does not parse the fields.
/// @throws std::invalid_argument naming the text line when a line 1 is not followed by
///         a line 2, a line 2 has no line 1, or a name is not followed by a line 1.
std::vector<TleLines> splitTleText(std::istream& text);

}  // namespace flatsat::sim
