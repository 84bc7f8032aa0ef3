// SPDX-License-Identifier: Apache-2.0
#include "bus/Params.hpp"

#include "bus/NearestName.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <numbers>
#include <sstream>

namespace flatsat::bus {

namespace {

struct UnitDef {
  std::string_view name;
  std::string_view dimension;
  double to_si;
};

constexpr double kDeg = std::numbers::pi / 180.0;

// Units a value may be written in. The key's own unit must be listed too;
// a key whose unit is not listed takes plain numbers only.
constexpr UnitDef kUnits[] = {
    {"-", "1", 1.0},
    {"m", "length", 1.0},         {"km", "length", 1e3},
    {"s", "time", 1.0},           {"ms", "time", 1e-3},        {"min", "time", 60.0},
    {"h", "time", 3600.0},        {"d", "time", 86400.0},
    {"rad", "angle", 1.0},        {"deg", "angle", kDeg},      {"arcsec", "angle", kDeg / 3600},
    {"T", "field", 1.0},          {"mT", "field", 1e-3},       {"uT", "field", 1e-6},
    {"nT", "field", 1e-9},        {"G", "field", 1e-4},
    {"rad/s", "rate", 1.0},       {"deg/s", "rate", kDeg},     {"deg/h", "rate", kDeg / 3600},
    {"rpm", "rate", 2 * std::numbers::pi / 60},
    {"N m", "torque", 1.0},       {"mN m", "torque", 1e-3},    {"uN m", "torque", 1e-6},
    {"N m s", "momentum", 1.0},   {"mN m s", "momentum", 1e-3},
    {"kg m^2", "inertia", 1.0},
    {"A m^2", "dipole", 1.0},
    {"1/s", "frequency", 1.0},    {"Hz", "frequency", 1.0},
    {"1/s^2", "frequency2", 1.0},
    {"N m/rad", "stiffness", 1.0},
    {"N m s/rad", "damping", 1.0},
    {"m^2", "area", 1.0},         {"cm^2", "area", 1e-4},
    {"N", "force", 1.0},          {"mN", "force", 1e-3},       {"uN", "force", 1e-6},
    {"N s", "impulse", 1.0},      {"mN s", "impulse", 1e-3},   {"uN s", "impulse", 1e-6},
    {"kg", "mass", 1.0},          {"g", "mass", 1e-3},
    {"kg/m^3", "density", 1.0},   {"g/cm^3", "density", 1e3},
    {"W/m^2", "irradiance", 1.0},
};

const UnitDef* findUnit(std::string_view name) {
  for (const auto& unit : kUnits) {
    if (unit.name == name) return &unit;
  }
  return nullptr;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

}  // namespace

std::string ConfigProblems::joined() const {
  std::ostringstream out;
  for (const auto& problem : problems_) out << "  " << problem << '\n';
  return out.str();
}

ParamReader::ParamReader(YAML::Node node, std::string file, std::string path,
                         ConfigProblems& problems)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)), problems_(problems) {
  if (node_.IsDefined() && !node_.IsNull() && !node_.IsMap()) {
    problem("", "must be a mapping of key: value");
  }
}

std::string ParamReader::keyPath(const std::string& key) const {
  if (key.empty()) return path_.empty() ? "(top level)" : path_;
  return path_.empty() ? key : path_ + "." + key;
}

std::string ParamReader::where(const YAML::Node& node) const {
  const auto mark = node.Mark();
  if (mark.line < 0) return file_;
  return file_ + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

void ParamReader::problem(const std::string& key, const std::string& reason) {
  if (!key.empty()) failed_.push_back(key);
  const YAML::Node node = (!key.empty() && node_.IsMap() && node_[key]) ? node_[key] : node_;
  problems_.add(where(node) + ": " + keyPath(key) + ": " + reason);
}

void ParamReader::problems(const std::vector<std::string>& field_reasons) {
  for (const auto& field_reason : field_reasons) {
    const auto colon = field_reason.find(':');
    const auto field = field_reason.substr(0, colon);
    if (colon != std::string::npos && failed(field)) continue;
    // A validate() field named after a YAML key points at that key's line.
    if (colon != std::string::npos && node_.IsMap() && node_[field]) {
      problem(field, trim(field_reason.substr(colon + 1)));
    } else {
      problem("", field_reason);
    }
  }
}

bool ParamReader::failed(const std::string& key) const {
  return std::find(failed_.begin(), failed_.end(), key) != failed_.end();
}

bool ParamReader::has(const std::string& key) const {
  return node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
}

YAML::Node ParamReader::lookup(const std::string& key) {
  used_.push_back(key);
  if (!node_.IsMap()) return YAML::Node();
  return node_[key];
}

ParamReader ParamReader::section(const std::string& key) {
  return ParamReader(lookup(key), file_, keyPath(key), problems_);
}

std::vector<ParamReader> ParamReader::list(const std::string& key) {
  std::vector<ParamReader> entries;
  const YAML::Node node = lookup(key);
  if (!node.IsDefined() || node.IsNull()) return entries;
  if (!node.IsSequence()) {
    problem(key, "expected a list");
    return entries;
  }
  for (std::size_t i = 0; i < node.size(); ++i) {
    entries.emplace_back(node[i], file_, keyPath(key) + "[" + std::to_string(i) + "]", problems_);
  }
  return entries;
}

void ParamReader::finish() {
  if (!node_.IsMap()) return;
  for (const auto& entry : node_) {
    if (!entry.first.IsScalar()) {  // e.g. `? {a: 1}`: found by tests/fuzz (scenario)
      problems_.add(where(entry.first) + ": " + keyPath("") + ": a key must be a plain word");
      continue;
    }
    const auto key = entry.first.as<std::string>();
    if (std::find(used_.begin(), used_.end(), key) == used_.end()) {
      problems_.add(where(entry.first) + ": " + keyPath(key) + ": unknown key" + didYouMean(key, used_));
    }
  }
}

bool ParamReader::scalarInUnit(const YAML::Node& node, const std::string& key,
                               std::string_view unit, double& out) {
  if (!node.IsScalar()) {
    problem(key, "expected a number");
    return false;
  }
  const std::string text = node.Scalar();
  char* end = nullptr;
  const double number = std::strtod(text.c_str(), &end);
  if (end == text.c_str()) {
    problem(key, "'" + text + "' is not a number");
    return false;
  }
  const std::string suffix = trim(end);
  if (!std::isfinite(number)) {
    problem(key, "'" + text + "' is not finite");
    return false;
  }
  if (suffix.empty()) {
    out = number;
    return true;
  }
  const UnitDef* given = findUnit(suffix);
  const UnitDef* wanted = findUnit(unit);
  if (given == nullptr) {
    problem(key, "unknown unit '" + suffix + "' (expected " + std::string(unit) + ")");
    return false;
  }
  if (wanted == nullptr || given->dimension != wanted->dimension) {
    problem(key, "wrong unit '" + suffix + "': expected " + std::string(unit) +
                     (wanted ? " or a unit of " + std::string(wanted->dimension) : ""));
    return false;
  }
  out = number * given->to_si / wanted->to_si;
  return true;
}

void ParamReader::read(const std::string& key, double& value, std::string_view unit) {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined() || node.IsNull()) return;
  double v;
  if (scalarInUnit(node, key, unit, v)) value = v;
}

void ParamReader::read(const std::string& key, Eigen::Vector3d& value, std::string_view unit) {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined() || node.IsNull()) return;
  if (!node.IsSequence() || node.size() != 3) return problem(key, "expected a list of 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    if (!scalarInUnit(node[i], key, unit, v[i])) return;
  }
  value = v;
}

void ParamReader::read(const std::string& key, Eigen::Vector4d& value, std::string_view unit) {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined() || node.IsNull()) return;
  double scalar;
  if (node.IsScalar()) {
    if (scalarInUnit(node, key, unit, scalar)) value.setConstant(scalar);
    return;
  }
  if (!node.IsSequence() || node.size() == 0 || node.size() > 4) {
    return problem(key, "expected a number or a list of 1 to 4 numbers");
  }
  Eigen::Vector4d v = Eigen::Vector4d::Zero();
  for (std::size_t i = 0; i < node.size(); ++i) {
    if (!scalarInUnit(node[i], key, unit, v[static_cast<int>(i)])) return;
  }
  value = v;
}

void ParamReader::read(const std::string& key, Eigen::Matrix3d& value, std::string_view unit) {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined() || node.IsNull()) return;
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  if (node.IsSequence() && node.size() == 3 && node[0].IsScalar()) {
    for (int i = 0; i < 3; ++i) {
      if (!scalarInUnit(node[i], key, unit, m(i, i))) return;
    }
  } else if (node.IsSequence() && node.size() == 3) {
    for (int r = 0; r < 3; ++r) {
      if (!node[r].IsSequence() || node[r].size() != 3) {
        return problem(key, "expected 3 rows of 3 numbers, or 3 diagonal numbers");
      }
      for (int c = 0; c < 3; ++c) {
        if (!scalarInUnit(node[r][c], key, unit, m(r, c))) return;
      }
    }
  } else {
    return problem(key, "expected 3 rows of 3 numbers, or 3 diagonal numbers");
  }
  value = m;
}

void ParamReader::read(const std::string& key, Eigen::Matrix<double, 3, 4>& value, int& count) {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined() || node.IsNull()) return;
  if (!node.IsSequence() || node.size() == 0 || node.size() > 4) {
    return problem(key, "expected a list of 1 to 4 axes [x, y, z]");
  }
  Eigen::Matrix<double, 3, 4> axes = Eigen::Matrix<double, 3, 4>::Zero();
  for (std::size_t i = 0; i < node.size(); ++i) {
    if (!node[i].IsSequence() || node[i].size() != 3) {
      return problem(key, "axis " + std::to_string(i + 1) + ": expected [x, y, z]");
    }
    for (int r = 0; r < 3; ++r) {
      if (!scalarInUnit(node[i][r], key, "-", axes(r, static_cast<int>(i)))) return;
    }
  }
  value = axes;
  count = static_cast<int>(node.size());
}

void ParamReader::read(const std::string& key, Eigen::Quaterniond& value) {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined() || node.IsNull()) return;
  if (!node.IsSequence() || node.size() != 4) {
    return problem(key, "expected a quaternion [w, x, y, z] (Hamilton, scalar first)");
  }
  double q[4];
  for (int i = 0; i < 4; ++i) {
    if (!scalarInUnit(node[i], key, "-", q[i])) return;
  }
  Eigen::Quaterniond quat(q[0], q[1], q[2], q[3]);
  if (std::abs(quat.norm() - 1.0) > 1e-6) {
    return problem(key, "quaternion norm is " + std::to_string(quat.norm()) + ", expected 1");
  }
  value = quat.normalized();
}

void ParamReader::read(const std::string& key, bool& value) {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined() || node.IsNull()) return;
  try {
    value = node.as<bool>();
  } catch (const YAML::Exception&) {
    problem(key, "expected true or false");
  }
}

void ParamReader::read(const std::string& key, std::uint64_t& value) {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined() || node.IsNull()) return;
  const std::string text = node.IsScalar() ? node.Scalar() : "";
  char* end = nullptr;
  errno = 0;
  const auto v = std::strtoull(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || text[0] == '-' || errno == ERANGE) {
    return problem(key, "expected a non-negative integer, got '" + text + "'");
  }
  value = v;
}

void ParamReader::read(const std::string& key, std::uint32_t& value) {
  std::uint64_t v = value;
  read(key, v);
  if (v > 0xffffffffULL) return problem(key, "too large");
  value = static_cast<std::uint32_t>(v);
}

void ParamReader::read(const std::string& key, int& value) {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined() || node.IsNull()) return;
  try {
    value = node.as<int>();
  } catch (const YAML::Exception&) {
    problem(key, "expected an integer");
  }
}

void ParamReader::read(const std::string& key, std::string& value) {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined() || node.IsNull()) return;
  if (!node.IsScalar()) return problem(key, "expected a string");
  value = node.Scalar();
}

void ParamReader::read(const std::string& key, std::vector<std::string>& value) {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined() || node.IsNull()) return;
  if (!node.IsSequence()) return problem(key, "expected a list of strings");
  std::vector<std::string> words;
  for (const auto& element : node) {
    if (!element.IsScalar()) return problem(key, "expected a list of strings");
    words.push_back(element.Scalar());
  }
  value = std::move(words);
}

}  // namespace flatsat::bus
