// SPDX-License-Identifier: Apache-2.0
#include "rig/JsonFile.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace flatsat::rig {

namespace fs = std::filesystem;

void writeJsonAtomically(const std::string& file, const nlohmann::ordered_json& content) {
  const std::string partial = file + ".partial";
  {
    std::ofstream out(partial);
    out << content.dump(2) << "\n";
    if (!out.flush()) {
      std::error_code ignored;
      fs::remove(partial, ignored);
      throw std::runtime_error(partial + ": cannot write");
    }
  }
  std::error_code error;
  fs::rename(partial, file, error);
  if (error) throw std::runtime_error(file + ": cannot replace: " + error.message());
}

nlohmann::ordered_json readJsonFile(const std::string& file, const std::string& unreadable_hint) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file + ": cannot read" + (unreadable_hint.empty() ? "" : " (" + unreadable_hint + ")"));
  nlohmann::ordered_json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(file + ": " + e.what());
  }
  return j;
}

}  // namespace flatsat::rig
