// SPDX-License-Identifier: Apache-2.0
#include "sim/Tle.hpp"

#include <charconv>
#include <cmath>
#include <optional>
#include <span>
#include <stdexcept>
#include <string_view>

#include "sim/Format.hpp"
#include "sim/Time.hpp"

namespace flatsat::sim {
namespace {

constexpr std::size_t kLineLength = 69;

/// Where a field is: line 1 or 2 and its 1-based inclusive columns.
struct Field {
  int line;
  std::size_t first;
  std::size_t last;
  const char* name;
};

std::string where(const Field& f) {
  const std::string columns = f.first == f.last ? "column " + std::to_string(f.first)
                                                : "columns " + std::to_string(f.first) + "-" + std::to_string(f.last);
  return "line " + std::to_string(f.line) + ", " + columns;
}

std::string_view text(const std::string& line, const Field& f) {
  return std::string_view(line).substr(f.first - 1, f.last - f.first + 1);
}

[[noreturn]] void reject(const std::string& line, const Field& f, const std::string& reason) {
  throw std::invalid_argument("TLE " + where(f) + " (" + f.name + "): \"" + std::string(text(line, f)) + "\" " +
                              reason);
}

bool isDigit(char c) { return c >= '0' && c <= '9'; }

std::string_view trimBlanks(std::string_view s) {
  const std::size_t first = s.find_first_not_of(' ');
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(' ') - first + 1);
}

/// A decimal number: optional sign, digits with at most one point, blanks around it.
double decimal(const std::string& line, const Field& f) {
  std::string_view s = trimBlanks(text(line, f));
  const bool negative = !s.empty() && s.front() == '-';
  if (!s.empty() && (s.front() == '+' || s.front() == '-')) s.remove_prefix(1);
  int digits = 0;
  int points = 0;
  for (const char c : s) {
    digits += isDigit(c) ? 1 : 0;
    points += c == '.' ? 1 : 0;
    if (!isDigit(c) && c != '.') reject(line, f, "is not a decimal number");
  }
  if (digits == 0 || points > 1) reject(line, f, "is not a decimal number");
  double value = 0.0;
  std::from_chars(s.data(), s.data() + s.size(), value);
  return negative ? -value : value;
}

/// A right-justified unsigned integer; an all-blank field is `blank_value` when given.
int integer(const std::string& line, const Field& f, std::optional<int> blank_value = std::nullopt) {
  const std::string_view s = trimBlanks(text(line, f));
  if (s.empty()) {
    if (blank_value) return *blank_value;
    reject(line, f, "is blank");
  }
  int value = 0;
  for (const char c : s) {
    if (!isDigit(c)) reject(line, f, "is not an unsigned integer");
    value = value * 10 + (c - '0');
  }
  return value;
}

/// Digits after an implied leading "0."; blanks read as zeros (Vallado's twoline2rv).
std::string impliedFraction(const std::string& line, const Field& f) {
  std::string fraction = "0.";
  for (const char c : text(line, f)) {
    if (c != ' ' && !isDigit(c)) reject(line, f, "must be digits after an implied decimal point");
    fraction += c == ' ' ? '0' : c;
  }
  return fraction;
}

/// The assumed-decimal exponent form "±MMMMM±E" = ±0.MMMMM × 10^±E (d2n/dt2, B*).
/// Computed as mantissa · 10^E like Vallado's twoline2rv so that the double matches.
double assumedDecimal(const std::string& line, const Field& f) {
  const std::string_view s = text(line, f);
  const char sign = s[0];
  const char exponent_sign = s[6];
  const char exponent_digit = s[7];
  if ((sign != ' ' && sign != '+' && sign != '-') ||
      (exponent_sign != ' ' && exponent_sign != '+' && exponent_sign != '-') ||
      (exponent_digit != ' ' && !isDigit(exponent_digit))) {
    reject(line, f, "is not of the form ±MMMMM±E");
  }
  const Field mantissa_field{f.line, f.first + 1, f.first + 5, f.name};
  const std::string mantissa = impliedFraction(line, mantissa_field);
  double mantissa_value = 0.0;
  std::from_chars(mantissa.data(), mantissa.data() + mantissa.size(), mantissa_value);
  if (sign == '-') mantissa_value = -mantissa_value;
  const int exponent = (exponent_digit == ' ' ? 0 : exponent_digit - '0') * (exponent_sign == '-' ? -1 : 1);
  return mantissa_value * std::pow(10.0, exponent);
}

/// Catalogue number: up to five digits, or Alpha-5 (a letter for the two leading
/// digits, A = 10 … Z = 33 without I and O, then four digits).
int catalogNumber(const std::string& line, const Field& f) {
  const char lead = text(line, f)[0];
  if (lead < 'A' || lead > 'Z') return integer(line, f);
  if (lead == 'I' || lead == 'O') reject(line, f, "is not an Alpha-5 number (I and O are not used)");
  const int value = 10 + (lead - 'A') - (lead > 'I' ? 1 : 0) - (lead > 'O' ? 1 : 0);
  const Field digits{f.line, f.first + 1, f.last, f.name};
  const std::string_view rest = text(line, digits);
  for (const char c : rest) {
    if (!isDigit(c)) reject(line, f, "is not an Alpha-5 number (a letter and four digits)");
  }
  return value * 10000 + integer(line, digits);
}

/// Modulo-10 sum of columns 1-68: digits count their value, '-' counts 1.
int checksumOf(const std::string& line) {
  int sum = 0;
  for (std::size_t i = 0; i + 1 < kLineLength; ++i) {
    if (isDigit(line[i])) sum += line[i] - '0';
    if (line[i] == '-') sum += 1;
  }
  return sum % 10;
}

void checkLayout(const std::string& line, int number, TleChecksum checksum) {
  const std::string name = "TLE line " + std::to_string(number);
  if (line.size() < kLineLength) {
    throw std::invalid_argument(name + ": " + std::to_string(line.size()) + " characters, a TLE line has " +
                                std::to_string(kLineLength));
  }
  const Field line_number{number, 1, 1, "line number"};
  if (line[0] != static_cast<char>('0' + number)) reject(line, line_number, "should be " + std::to_string(number));
  // Blank separators between the fields: a shifted field shows up here first.
  static constexpr std::size_t kSeparators1[] = {2, 9, 18, 33, 44, 53, 62, 64};
  static constexpr std::size_t kSeparators2[] = {2, 8, 17, 26, 34, 43, 52};
  const std::span<const std::size_t> separators =
      number == 1 ? std::span<const std::size_t>(kSeparators1) : std::span<const std::size_t>(kSeparators2);
  for (const std::size_t column : separators) {
    if (line[column - 1] != ' ') reject(line, Field{number, column, column, "separator"}, "should be blank");
  }
  if (checksum == TleChecksum::kIgnore) return;
  const Field field{number, 69, 69, "checksum"};
  if (!isDigit(line[68])) reject(line, field, "is not a digit");
  if (line[68] - '0' != checksumOf(line)) {
    reject(line, field, "does not match the line, whose checksum is " + std::to_string(checksumOf(line)));
  }
}

std::string range(double value, const char* interval) { return formatNumber(value) + " not in " + interval; }

}  // namespace

std::vector<std::string> Tle::validate() const {
  std::vector<std::string> errors;
  const auto check = [&errors](bool ok, const char* field, const std::string& reason) {
    if (!ok) errors.push_back(std::string(field) + ": " + reason);
  };
  check(catalog_number >= 0 && catalog_number <= 339999, "catalog_number (line 1, columns 3-7)",
        range(catalog_number, "0..339999"));
  check(classification == 'U' || classification == 'C' || classification == 'S', "classification (line 1, column 8)",
        std::string("'") + classification + "' is not U, C or S");
  check(epoch_year >= 1957 && epoch_year <= 2056, "epoch_year (line 1, columns 19-20)",
        range(epoch_year, "1957..2056"));
  const double days_in_year = isLeapYear(epoch_year) ? 366.0 : 365.0;
  check(epoch_day >= 1.0 && epoch_day < days_in_year + 1.0, "epoch_day (line 1, columns 21-32)",
        range(epoch_day, isLeapYear(epoch_year) ? "[1, 367)" : "[1, 366)"));
  check(std::isfinite(mean_motion_dot), "mean_motion_dot (line 1, columns 34-43)", "not finite");
  check(std::isfinite(mean_motion_ddot), "mean_motion_ddot (line 1, columns 45-52)", "not finite");
  check(std::isfinite(bstar), "bstar (line 1, columns 54-61)", "not finite");
  check(ephemeris_type >= 0 && ephemeris_type <= 9, "ephemeris_type (line 1, column 63)",
        range(ephemeris_type, "0..9"));
  check(element_set_number >= 0 && element_set_number <= 9999, "element_set_number (line 1, columns 65-68)",
        range(element_set_number, "0..9999"));
  check(inclination_deg >= 0.0 && inclination_deg <= 180.0, "inclination_deg (line 2, columns 9-16)",
        range(inclination_deg, "[0, 180]"));
  check(raan_deg >= 0.0 && raan_deg < 360.0, "raan_deg (line 2, columns 18-25)", range(raan_deg, "[0, 360)"));
  check(eccentricity >= 0.0 && eccentricity < 1.0, "eccentricity (line 2, columns 27-33)",
        range(eccentricity, "[0, 1)"));
  check(arg_perigee_deg >= 0.0 && arg_perigee_deg < 360.0, "arg_perigee_deg (line 2, columns 35-42)",
        range(arg_perigee_deg, "[0, 360)"));
  check(mean_anomaly_deg >= 0.0 && mean_anomaly_deg < 360.0, "mean_anomaly_deg (line 2, columns 44-51)",
        range(mean_anomaly_deg, "[0, 360)"));
  check(mean_motion_rev_day > 0.0 && std::isfinite(mean_motion_rev_day), "mean_motion_rev_day (line 2, columns 53-63)",
        formatNumber(mean_motion_rev_day) + " must be positive");
  check(revolution_number >= 0 && revolution_number <= 99999, "revolution_number (line 2, columns 64-68)",
        range(revolution_number, "0..99999"));
  return errors;
}

Tle parseTle(const std::string& line1, const std::string& line2, TleChecksum checksum) {
  checkLayout(line1, 1, checksum);
  checkLayout(line2, 2, checksum);

  Tle tle;
  tle.catalog_number = catalogNumber(line1, {1, 3, 7, "catalogue number"});
  const char classification = line1[7];
  tle.classification = classification == ' ' ? 'U' : classification;
  tle.international_designator = std::string(trimBlanks(text(line1, {1, 10, 17, "international designator"})));
  const int two_digit_year = integer(line1, {1, 19, 20, "epoch year"});
  // Two-digit years: 1957 (Sputnik) to 2056, the convention of STR#3 and Vallado.
  tle.epoch_year = two_digit_year < 57 ? 2000 + two_digit_year : 1900 + two_digit_year;
  tle.epoch_day = decimal(line1, {1, 21, 32, "epoch day of year"});
  tle.mean_motion_dot = decimal(line1, {1, 34, 43, "first derivative of the mean motion / 2"});
  tle.mean_motion_ddot = assumedDecimal(line1, {1, 45, 52, "second derivative of the mean motion / 6"});
  tle.bstar = assumedDecimal(line1, {1, 54, 61, "B* drag term"});
  tle.ephemeris_type = integer(line1, {1, 63, 63, "ephemeris type"}, 0);
  tle.element_set_number = integer(line1, {1, 65, 68, "element set number"}, 0);

  const Field catalog2{2, 3, 7, "catalogue number"};
  if (catalogNumber(line2, catalog2) != tle.catalog_number) {
    reject(line2, catalog2, "differs from line 1's catalogue number " + std::to_string(tle.catalog_number));
  }
  tle.inclination_deg = decimal(line2, {2, 9, 16, "inclination"});
  tle.raan_deg = decimal(line2, {2, 18, 25, "right ascension of the ascending node"});
  const std::string eccentricity = impliedFraction(line2, {2, 27, 33, "eccentricity"});
  std::from_chars(eccentricity.data(), eccentricity.data() + eccentricity.size(), tle.eccentricity);
  tle.arg_perigee_deg = decimal(line2, {2, 35, 42, "argument of perigee"});
  tle.mean_anomaly_deg = decimal(line2, {2, 44, 51, "mean anomaly"});
  tle.mean_motion_rev_day = decimal(line2, {2, 53, 63, "mean motion"});
  tle.revolution_number = integer(line2, {2, 64, 68, "revolution number"}, 0);

  const std::vector<std::string> errors = tle.validate();
  if (!errors.empty()) {
    std::string message = "TLE of catalogue number " + std::to_string(tle.catalog_number) + ": " + errors.front();
    for (std::size_t i = 1; i < errors.size(); ++i) message += "; " + errors[i];
    throw std::invalid_argument(message);
  }
  return tle;
}

std::vector<TleLines> splitTleText(std::istream& in) {
  std::vector<TleLines> sets;
  TleLines pending;
  bool have_line1 = false;
  std::string name;
  int name_line = 0;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line.erase(line.find_last_not_of(" \t\r") + 1);
    if (line.empty() || line[0] == '#') continue;
    const bool is_line1 = line.rfind("1 ", 0) == 0;
    const bool is_line2 = line.rfind("2 ", 0) == 0;
    const std::string at = "line " + std::to_string(number) + ": ";
    if (have_line1) {
      if (!is_line2) {
        throw std::invalid_argument(at + "expected line 2 of the element set whose line 1 is line " +
                                    std::to_string(pending.line_number));
      }
      pending.line2 = line;
      sets.push_back(pending);
      have_line1 = false;
    } else if (is_line1) {
      pending = TleLines{name, line, "", number};
      have_line1 = true;
      name.clear();
    } else if (is_line2) {
      throw std::invalid_argument(at + "a TLE line 2 without a line 1 before it");
    } else if (!name.empty()) {
      throw std::invalid_argument(at + "expected line 1 of the element set named on line " + std::to_string(name_line));
    } else {
      name = line.rfind("0 ", 0) == 0 ? line.substr(2) : line;
      name_line = number;
    }
  }
  if (have_line1) {
    throw std::invalid_argument("line " + std::to_string(pending.line_number) + ": a TLE line 1 without its line 2");
  }
  if (!name.empty()) {
    throw std::invalid_argument("line " + std::to_string(name_line) + ": a name without an element set after it");
  }
  return sets;
}

}  // namespace flatsat::sim
