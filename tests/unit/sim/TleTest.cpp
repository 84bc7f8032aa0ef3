// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include <catch2/catch.hpp>

#include "sim/Tle.hpp"

using namespace flatsat::sim;
using Catch::Matchers::Contains;

namespace {

// Vanguard 1 (00005), the first set of Vallado's verification file.
const std::string kLine1 = "1 00005U 58002B   00179.78495062  .00000023  00000-0  28098-4 0  4753";
const std::string kLine2 = "2 00005  34.2682 348.7242 1859667 331.7664  19.3264 10.82419157413667";

/// The line with columns [first, first + text.size()) (1-based) replaced and the
/// checksum recomputed: digits count their value, '-' counts one, modulo 10.
std::string edited(std::string line, std::size_t first, const std::string& text) {
  line.replace(first - 1, text.size(), text);
  int sum = 0;
  for (std::size_t i = 0; i < 68; ++i) {
    if (line[i] >= '0' && line[i] <= '9') sum += line[i] - '0';
    if (line[i] == '-') sum += 1;
  }
  line[68] = static_cast<char>('0' + sum % 10);
  return line;
}

}  // namespace

SCENARIO("parseTle reads every field by column", "[sim][sgp4][tle]") {
  GIVEN("Vanguard 1's element set") {
    const Tle tle = parseTle(kLine1, kLine2);
    THEN("each field has the value written in its columns") {
      CHECK(tle.catalog_number == 5);
      CHECK(tle.classification == 'U');
      CHECK(tle.international_designator == "58002B");
      CHECK(tle.epoch_year == 2000);
      CHECK(tle.epoch_day == 179.78495062);
      CHECK(tle.mean_motion_dot == 0.00000023);
      CHECK(tle.mean_motion_ddot == 0.0);
      CHECK(tle.bstar == Approx(2.8098e-5).epsilon(1e-15));
      CHECK(tle.ephemeris_type == 0);
      CHECK(tle.element_set_number == 475);
      CHECK(tle.inclination_deg == 34.2682);
      CHECK(tle.raan_deg == 348.7242);
      CHECK(tle.eccentricity == 0.1859667);
      CHECK(tle.arg_perigee_deg == 331.7664);
      CHECK(tle.mean_anomaly_deg == 19.3264);
      CHECK(tle.mean_motion_rev_day == 10.82419157);
      CHECK(tle.revolution_number == 41366);
    }
  }
  GIVEN("negative derivatives and drag terms (SL-6 R/B 16925, Molniya 1-83 21897)") {
    const Tle sl6 = parseTle("1 16925U 86065D   06151.67415771  .02550794 -30915-6  18784-3 0  4486",
                             "2 16925  62.0906 295.0239 5596327 245.1593  47.9690  4.88511875148616");
    const Tle molniya = parseTle("1 21897U 92011A   06176.02341244 -.00001273  00000-0 -13525-3 0  3044",
                                 "2 21897  62.1749 198.0096 7421690 253.0462  20.1561  2.01269994104880");
    THEN("the signs and the assumed-decimal exponents are applied") {
      CHECK(sl6.mean_motion_ddot == Approx(-3.0915e-7).epsilon(1e-15));
      CHECK(sl6.bstar == Approx(1.8784e-4).epsilon(1e-15));
      CHECK(molniya.mean_motion_dot == -0.00001273);
      CHECK(molniya.bstar == Approx(-1.3525e-4).epsilon(1e-15));
    }
  }
  GIVEN("STR #3's original SDP4 test set, with blank designator, ephemeris type and numbers") {
    const Tle tle = parseTle("1 11801U          80230.29629788  .01431103  00000-0  14311-1      13",
                             "2 11801  46.7916 230.4354 7318036  47.4722  10.4117  2.28537848    13");
    THEN("blanks read as empty or zero, the year as 1980") {
      CHECK(tle.international_designator.empty());
      CHECK(tle.epoch_year == 1980);
      CHECK(tle.ephemeris_type == 0);
      CHECK(tle.element_set_number == 1);
      CHECK(tle.revolution_number == 1);
      CHECK(tle.bstar == Approx(0.014311).epsilon(1e-15));
    }
  }
  GIVEN("Alpha-5 catalogue numbers") {
    THEN("the letter stands for the two leading digits, skipping I and O") {
      CHECK(parseTle(edited(kLine1, 3, "A0005"), edited(kLine2, 3, "A0005")).catalog_number == 100005);
      CHECK(parseTle(edited(kLine1, 3, "J1234"), edited(kLine2, 3, "J1234")).catalog_number == 181234);
      CHECK(parseTle(edited(kLine1, 3, "Z9999"), edited(kLine2, 3, "Z9999")).catalog_number == 339999);
      CHECK_THROWS_WITH(parseTle(edited(kLine1, 3, "I0005"), edited(kLine2, 3, "I0005")),
                        Contains("line 1, columns 3-7 (catalogue number)") && Contains("I and O"));
    }
  }
}

SCENARIO("parseTle names the line, the columns and the field of every error", "[sim][sgp4][tle]") {
  GIVEN("broken layouts") {
    THEN("short lines, swapped lines and filled separators are reported") {
      CHECK_THROWS_WITH(parseTle(kLine1.substr(0, 68), kLine2), "TLE line 1: 68 characters, a TLE line has 69");
      CHECK_THROWS_WITH(parseTle(kLine2, kLine1), Contains("TLE line 1, column 1 (line number): \"2\" should be 1"));
      CHECK_THROWS_WITH(parseTle(edited(kLine1, 9, "X"), kLine2),
                        Contains("TLE line 1, column 9 (separator): \"X\" should be blank"));
    }
  }
  GIVEN("a checksum that does not match") {
    const std::string line1 = kLine1.substr(0, 68) + "4";
    THEN("it is an error unless checksums are ignored") {
      CHECK_THROWS_WITH(parseTle(line1, kLine2),
                        Contains("line 1, column 69 (checksum): \"4\" does not match the line, whose checksum is 3"));
      CHECK(parseTle(line1, kLine2, TleChecksum::kIgnore).catalog_number == 5);
    }
  }
  GIVEN("malformed numbers") {
    THEN("the message quotes the columns' text") {
      CHECK_THROWS_WITH(parseTle(kLine1, edited(kLine2, 9, " 34.2x82")),
                        "TLE line 2, columns 9-16 (inclination): \" 34.2x82\" is not a decimal number");
      CHECK_THROWS_WITH(parseTle(edited(kLine1, 19, "0O"), kLine2),
                        Contains("line 1, columns 19-20 (epoch year): \"0O\" is not an unsigned integer"));
      CHECK_THROWS_WITH(parseTle(edited(kLine1, 54, " 28098*4"), kLine2),
                        Contains("line 1, columns 54-61 (B* drag term): \" 28098*4\" is not of the form"));
      CHECK_THROWS_WITH(parseTle(kLine1, edited(kLine2, 27, "18596x7")),
                        Contains("line 2, columns 27-33 (eccentricity)"));
      CHECK_THROWS_WITH(parseTle(kLine1, edited(kLine2, 53, " 10.8.41915")),
                        Contains("line 2, columns 53-63 (mean motion)"));
    }
  }
  GIVEN("lines of different satellites") {
    THEN("the catalogue numbers must agree") {
      CHECK_THROWS_WITH(parseTle(kLine1, edited(kLine2, 3, "00006")),
                        Contains("line 2, columns 3-7 (catalogue number): \"00006\" differs from line 1's "
                                 "catalogue number 5"));
    }
  }
  GIVEN("values outside their ranges") {
    THEN("every violation is listed with its field and columns") {
      CHECK_THROWS_WITH(parseTle(kLine1, edited(edited(kLine2, 9, "190.0000"), 53, " 0.00000000")),
                        Contains("inclination_deg (line 2, columns 9-16): 190 not in [0, 180]") &&
                            Contains("mean_motion_rev_day (line 2, columns 53-63): 0 must be positive"));
    }
  }
}

TEST_CASE("Tle::validate lists every violation", "[sim][sgp4][tle]") {
  CHECK(Tle{}.validate().empty());
  Tle bad;
  bad.epoch_year = 1950;
  bad.epoch_day = 0.5;
  bad.eccentricity = 1.0;
  bad.raan_deg = 360.0;
  bad.bstar = std::nan("");
  const auto errors = bad.validate();
  REQUIRE(errors.size() == 5);
  CHECK_THAT(errors[0], Contains("epoch_year"));
  CHECK_THAT(errors[1], Contains("epoch_day"));
  CHECK_THAT(errors[2], Contains("bstar"));
  CHECK_THAT(errors[3], Contains("raan_deg"));
  CHECK_THAT(errors[4], Contains("eccentricity"));
}

SCENARIO("splitTleText finds the element sets of a text", "[sim][sgp4][tle]") {
  GIVEN("a three-line text with CRLF ends, comments and blank lines") {
    std::istringstream text("# header\r\n\r\n0 VANGUARD 1\r\n" + kLine1 + "\r\n" + kLine2 + "\r\n" + kLine1 + "\n" +
                            kLine2 + "\n");
    const auto sets = splitTleText(text);
    THEN("each set has its name, lines and line number") {
      REQUIRE(sets.size() == 2);
      CHECK(sets[0].name == "VANGUARD 1");
      CHECK(sets[0].line1 == kLine1);
      CHECK(sets[0].line2 == kLine2);
      CHECK(sets[0].line_number == 4);
      CHECK(sets[1].name.empty());
      CHECK(sets[1].line_number == 6);
    }
  }
  GIVEN("sets with missing lines") {
    THEN("the text line is named") {
      std::istringstream no_line2(kLine1 + "\n" + kLine1 + "\n");
      CHECK_THROWS_WITH(splitTleText(no_line2), "line 2: expected line 2 of the element set whose line 1 is line 1");
      std::istringstream no_line1("NAME\n" + kLine2 + "\n");
      CHECK_THROWS_WITH(splitTleText(no_line1), "line 2: a TLE line 2 without a line 1 before it");
      std::istringstream two_names("NAME\nOTHER NAME\n");
      CHECK_THROWS_WITH(splitTleText(two_names), "line 2: expected line 1 of the element set named on line 1");
      std::istringstream truncated(kLine1 + "\n");
      CHECK_THROWS_WITH(splitTleText(truncated), "line 1: a TLE line 1 without its line 2");
    }
  }
}

TEST_CASE("Vallado's verification file has valid checksums except its three edited sets", "[sim][sgp4][tle]") {
  std::ifstream in(std::string(FLATSAT_DATA_DIR) + "/sgp4/SGP4-VER.TLE");
  REQUIRE(in);
  std::set<int> failed;
  for (const TleLines& lines : splitTleText(in)) {
    try {
      parseTle(lines.line1, lines.line2);
    } catch (const std::invalid_argument& e) {
      CHECK_THAT(e.what(), Contains("(checksum)"));
      failed.insert(parseTle(lines.line1, lines.line2, TleChecksum::kIgnore).catalog_number);
    }
  }
  CHECK(failed == std::set<int>{33333, 33334, 33335});
}
