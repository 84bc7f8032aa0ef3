// SPDX-License-Identifier: Apache-2.0
#include "bus/ScenarioPlaces.hpp"

#include <map>

namespace flatsat::bus {
namespace {

std::string lineCol(const YAML::Mark& mark) {
  return std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

void findDuplicates(const YAML::Node& node, const std::string& path, const std::string& file,
                    std::vector<std::string>& out) {
  if (node.IsMap()) {
    std::map<std::string, int> first_line;
    for (const auto& entry : node) {
      if (!entry.first.IsScalar()) continue;
      const std::string key = entry.first.Scalar();
      const std::string key_path = path.empty() ? key : path + "." + key;
      if (const auto seen = first_line.find(key); seen != first_line.end()) {
        out.push_back(file + ":" + lineCol(entry.first.Mark()) + ": " + key_path + ": duplicate key (first on line " +
                      std::to_string(seen->second) + "); YAML would keep one of them without a word");
      } else {
        first_line.emplace(key, entry.first.Mark().line + 1);
      }
      findDuplicates(entry.second, key_path, file, out);
    }
  } else if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) findDuplicates(node[i], path + "[" + std::to_string(i) + "]", file, out);
  }
}

}  // namespace

std::string placeOf(const std::string& file, const std::string& key) {
  try {
    YAML::Node node = YAML::LoadFile(file);
    std::size_t start = 0;
    while (start <= key.size()) {
      const auto end = key.find_first_of(".[", start);
      const std::string part = key.substr(start, end - start);
      if (!part.empty()) {
        if (!node.IsMap() || !node[part]) return "";
        node = node[part];
      }
      if (end == std::string::npos) break;
      if (key[end] == '[') {
        const auto close = key.find(']', end);
        if (close == std::string::npos) return "";
        const std::size_t index = std::stoul(key.substr(end + 1, close - end - 1));
        if (!node.IsSequence() || index >= node.size()) return "";
        node = node[index];
        start = close + 1;
        if (start < key.size() && key[start] == '.') ++start;
      } else {
        start = end + 1;
      }
    }
    return lineCol(node.Mark());
  } catch (const std::exception&) {  // YAML errors, a malformed index
    return "";
  }
}

std::string placeProblem(const std::string& problem, const std::string& reported,
                         const std::vector<std::string>& files) {
  if (problem.rfind(reported, 0) != 0) return problem;
  const auto place_end = problem.find(": ", reported.size());
  if (place_end == std::string::npos) return problem;
  const auto key_end = problem.find(": ", place_end + 2);
  if (key_end == std::string::npos) return problem;
  const std::string key = problem.substr(place_end + 2, key_end - place_end - 2);
  const std::string rest = problem.substr(place_end + 2);
  if (key.find(' ') == std::string::npos) {  // "(top level)" has none to look for
    for (const auto& file : files) {
      if (const auto place = placeOf(file, key); !place.empty()) return file + ":" + place + ": " + rest;
    }
  }
  return files.size() > 1 ? reported + ": " + rest : problem;
}

std::vector<std::string> duplicateKeys(const YAML::Node& root, const std::string& file) {
  std::vector<std::string> out;
  findDuplicates(root, "", file, out);
  return out;
}

}  // namespace flatsat::bus
