// SPDX-License-Identifier: Apache-2.0
#include "sim/GeomagneticCoefficients.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "sim/Format.hpp"

namespace flatsat::sim {
namespace {

constexpr int kMaxDegree = GaussCoefficients::kMaxDegree;
// IGRF and WMM releases both predict the field for five years past their last epoch.
constexpr double kPredictionSpan_yr = 5.0;

[[noreturn]] void fail(const std::string& file, int line, const std::string& reason) {
  throw std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + reason);
}

bool parseNumber(const std::string& token, double& value) {
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end;
}

// Reads "n m" and checks that it names a coefficient of the given kind ('g' or 'h').
void readDegreeOrder(std::istringstream& words, char kind, const std::string& file, int line, int& n, int& m) {
  if (!(words >> n >> m)) fail(file, line, "expected degree n and order m");
  if (n < 1 || n > kMaxDegree || m < 0 || m > n || (kind == 'h' && m == 0)) {
    fail(file, line,
         std::string("no coefficient ") + kind + " " + std::to_string(n) + " " + std::to_string(m) +
             " (need 1 ≤ n ≤ 13, 0 ≤ m ≤ n, and m ≥ 1 for h)");
  }
}

void requireYear(double year, double first, double last, const std::string& file) {
  if (!(year >= first && year <= last)) {
    fail(file, 0,
         "decimal year " + formatNumber(year) + " is outside [" + formatNumber(first) + ", " + formatNumber(last) +
             "] covered by the file");
  }
}

// Every g_n^m and h_n^m (m ≥ 1) up to the highest degree read must have had a row.
void requireComplete(const std::array<std::array<bool, kMaxDegree + 1>, kMaxDegree + 1> (&seen)[2], int degree,
                     const std::string& file) {
  if (degree == 0) fail(file, 0, "no coefficient rows");
  for (int n = 1; n <= degree; ++n) {
    for (int m = 0; m <= n; ++m) {
      for (int kind = 0; kind < (m == 0 ? 1 : 2); ++kind) {
        if (!seen[kind][n][m]) {
          fail(file, 0,
               std::string("no \"") + "gh"[kind] + " " + std::to_string(n) + " " + std::to_string(m) +
                   "\" row although the file reaches degree " + std::to_string(degree));
        }
      }
    }
  }
}

// Header "g/h n m 1900.0 … 2025.0 2025-30": the epochs, then the label of the SV column.
std::vector<double> parseEpochs(std::istringstream& words, const std::string& file, int line) {
  std::string token;
  if (!(words >> token) || token != "n" || !(words >> token) || token != "m") {
    fail(file, line, "header must start with \"g/h n m\"");
  }
  std::vector<double> epochs;
  double epoch = 0.0;
  while (words >> token && parseNumber(token, epoch)) {
    if (!epochs.empty() && epoch <= epochs.back()) fail(file, line, "epochs must increase, found " + token);
    epochs.push_back(epoch);
  }
  if (epochs.size() < 2) fail(file, line, "header lists fewer than two epochs");
  if (token.empty() || parseNumber(token, epoch)) fail(file, line, "header lacks the secular-variation column");
  if (words >> token) fail(file, line, "unexpected header column after the secular variation: " + token);
  return epochs;
}

// The highest degree with a non-zero term, so that IGRF before 2000 runs at degree 10.
int effectiveDegree(const GaussCoefficients& c) {
  for (int n = c.degree; n > 1; --n) {
    for (int m = 0; m <= n; ++m) {
      if (c.g_nT[n][m] != 0.0 || c.h_nT[n][m] != 0.0 || c.g_dot_nT_yr[n][m] != 0.0 || c.h_dot_nT_yr[n][m] != 0.0) {
        return n;
      }
    }
  }
  return 1;
}

}  // namespace

GaussCoefficients igrf14Coefficients(const std::string& igrf_coeff_file, double decimal_year) {
  const std::string& file = igrf_coeff_file;
  std::ifstream in(file);
  if (!in) fail(file, 0, "cannot open the IGRF coefficient file");

  std::vector<double> epochs;
  struct Row {
    char kind;
    int n, m;
    std::vector<double> values;  // one per epoch, then the secular variation
  };
  std::vector<Row> rows;
  std::array<std::array<bool, kMaxDegree + 1>, kMaxDegree + 1> seen[2] = {};
  int degree = 0;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    std::istringstream words(text);
    std::string kind;
    if (!(words >> kind) || kind.front() == '#' || kind == "c/s") continue;
    if (kind == "g/h") {
      if (!epochs.empty()) fail(file, line, "second \"g/h n m\" header");
      epochs = parseEpochs(words, file, line);
      continue;
    }
    if (kind != "g" && kind != "h") fail(file, line, "row type \"" + kind + "\" is neither g nor h");
    if (epochs.empty()) fail(file, line, "coefficient row before the \"g/h n m\" header");
    Row row{kind[0], 0, 0, {}};
    readDegreeOrder(words, row.kind, file, line, row.n, row.m);
    bool& was_seen = seen[row.kind == 'h'][row.n][row.m];
    if (was_seen)
      fail(file, line, "second row for " + kind + " " + std::to_string(row.n) + " " + std::to_string(row.m));
    was_seen = true;
    std::string token;
    double value = 0.0;
    while (words >> token) {
      if (!parseNumber(token, value)) fail(file, line, "\"" + token + "\" is not a number");
      row.values.push_back(value);
    }
    if (row.values.size() != epochs.size() + 1) {
      fail(file, line,
           "expected " + std::to_string(epochs.size() + 1) +
               " values (one per epoch, then the secular variation), found " + std::to_string(row.values.size()));
    }
    degree = std::max(degree, row.n);
    rows.push_back(std::move(row));
  }
  if (epochs.empty()) fail(file, 0, "no \"g/h n m\" header line");
  requireComplete(seen, degree, file);
  requireYear(decimal_year, epochs.front(), epochs.back() + kPredictionSpan_yr, file);

  // Linear between the epochs around the year; the SV column after the last epoch.
  const std::size_t last = epochs.size() - 1;
  std::size_t k = 0;
  while (k < last && decimal_year >= epochs[k + 1]) ++k;
  GaussCoefficients c;
  c.degree = degree;
  c.decimal_year = decimal_year;
  for (const Row& row : rows) {
    const double slope =
        k == last ? row.values[last + 1] : (row.values[k + 1] - row.values[k]) / (epochs[k + 1] - epochs[k]);
    const double value = row.values[k] + (decimal_year - epochs[k]) * slope;
    (row.kind == 'g' ? c.g_nT : c.h_nT)[row.n][row.m] = value;
    (row.kind == 'g' ? c.g_dot_nT_yr : c.h_dot_nT_yr)[row.n][row.m] = slope;
  }
  c.degree = effectiveDegree(c);
  return c;
}

GaussCoefficients wmm2025Coefficients(const std::string& wmm_cof_file, double decimal_year) {
  const std::string& file = wmm_cof_file;
  std::ifstream in(file);
  if (!in) fail(file, 0, "cannot open the WMM coefficient file");

  std::string text;
  double epoch = 0.0;
  {
    std::string token;
    std::istringstream words;
    if (std::getline(in, text)) words.str(text);
    if (!(words >> token) || !parseNumber(token, epoch)) fail(file, 1, "header must start with the epoch, e.g. 2025.0");
  }
  GaussCoefficients c;
  std::array<std::array<bool, kMaxDegree + 1>, kMaxDegree + 1> seen[2] = {};
  int degree = 0;
  bool closed = false;
  for (int line = 2; !closed && std::getline(in, text); ++line) {
    if (text.rfind("9999", 0) == 0) {
      closed = true;
      continue;
    }
    std::istringstream words(text);
    int n = 0;
    int m = 0;
    readDegreeOrder(words, 'g', file, line, n, m);
    if (seen[0][n][m]) fail(file, line, "second row for n = " + std::to_string(n) + ", m = " + std::to_string(m));
    seen[0][n][m] = true;
    seen[1][n][m] = m > 0;
    std::array<double, 4> v{};  // g, h, ġ, ḣ
    std::string token;
    for (double& value : v) {
      if (!(words >> token)) fail(file, line, "expected n m g h gdot hdot");
      if (!parseNumber(token, value)) fail(file, line, "\"" + token + "\" is not a number");
    }
    if (words >> token) fail(file, line, "unexpected column after n m g h gdot hdot: " + token);
    c.g_nT[n][m] = v[0] + (decimal_year - epoch) * v[2];
    c.h_nT[n][m] = v[1] + (decimal_year - epoch) * v[3];
    c.g_dot_nT_yr[n][m] = v[2];
    c.h_dot_nT_yr[n][m] = v[3];
    degree = std::max(degree, n);
  }
  if (!closed) fail(file, 0, "no closing line of 9s (file cut short?)");
  requireComplete(seen, degree, file);
  requireYear(decimal_year, epoch, epoch + kPredictionSpan_yr, file);
  c.degree = degree;
  c.decimal_year = decimal_year;
  return c;
}

}  // namespace flatsat::sim
