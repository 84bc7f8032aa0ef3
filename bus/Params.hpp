// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Dense>
#include <yaml-cpp/yaml.h>

namespace flatsat::bus {

/// Every problem found while reading a configuration, each as
/// "file:line:col: key: reason".
class ConfigProblems {
 public:
  void add(std::string problem) { problems_.push_back(std::move(problem)); }
  bool empty() const { return problems_.empty(); }
  const std::vector<std::string>& list() const { return problems_; }
  std::string joined() const;

 private:
  std::vector<std::string> problems_;
};

/// Reads one YAML mapping into parameter fields (cFS-style table loading):
/// absent keys keep the struct's default, present ones must parse and carry
/// a compatible unit, and finish() reports every key nobody read. A number
/// is taken in the key's unit; a string "value unit" (e.g. "560 km",
/// "5 deg", "30 nT") is converted, and a unit of another dimension is an
/// error.
class ParamReader {
 public:
  ParamReader(YAML::Node node, std::string file, std::string path, ConfigProblems& problems);

  bool has(const std::string& key) const;
  /// A nested mapping (empty when absent).
  ParamReader section(const std::string& key);
  /// One reader per entry of a list of mappings (none when absent).
  std::vector<ParamReader> list(const std::string& key);
  /// Reports keys present in the mapping that no read() or section() asked for.
  void finish();
  /// Keys of a section two readers share that the other reader reads: finish() does not report them.
  void leave(const std::vector<std::string>& keys) { used_.insert(used_.end(), keys.begin(), keys.end()); }
  /// Reports a problem at `key` (or at the mapping itself when key is empty).
  void problem(const std::string& key, const std::string& reason);
  /// Reports each "field: reason" of a validate() at this mapping's path,
  /// except for a field that already has a problem or was excused.
  void problems(const std::vector<std::string>& field_reasons);
  /// True when a problem was reported at `key`.
  bool failed(const std::string& key) const;
  /// `key` is derived from one that failed (semi_major_axis_m from a misread
  /// altitude_m): its validate() reason would only repeat that error.
  void excuse(const std::string& key) { failed_.push_back(key); }

  void read(const std::string& key, double& value, std::string_view unit);
  void read(const std::string& key, Eigen::Vector3d& value, std::string_view unit);
  /// A scalar (every live entry) or a list of up to four values.
  void read(const std::string& key, Eigen::Vector4d& value, std::string_view unit);
  /// A 3x3 list of rows, or three diagonal values.
  void read(const std::string& key, Eigen::Matrix3d& value, std::string_view unit);
  /// A list of up to four 3-vectors (columns).
  void read(const std::string& key, Eigen::Matrix<double, 3, 4>& value, int& count);
  /// [w, x, y, z], normalised; must be within 1e-6 of unit norm.
  void read(const std::string& key, Eigen::Quaterniond& value);
  void read(const std::string& key, bool& value);
  void read(const std::string& key, int& value);
  void read(const std::string& key, std::uint32_t& value);
  void read(const std::string& key, std::uint64_t& value);
  void read(const std::string& key, std::string& value);
  void read(const std::string& key, std::vector<std::string>& value);

  const std::string& file() const { return file_; }
  std::string keyPath(const std::string& key) const;

 private:
  std::string where(const YAML::Node& node) const;
  bool scalarInUnit(const YAML::Node& node, const std::string& key, std::string_view unit,
                    double& out);
  YAML::Node lookup(const std::string& key);

  YAML::Node node_;
  std::string file_;
  std::string path_;
  ConfigProblems& problems_;
  std::vector<std::string> used_;
  std::vector<std::string> failed_;
};

}  // namespace flatsat::bus
