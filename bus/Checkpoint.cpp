// SPDX-License-Identifier: Apache-2.0
#include "bus/Checkpoint.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace flatsat::bus {

namespace fs = std::filesystem;

void writeCheckpoint(const std::string& file, const std::string& component, std::uint64_t step,
                     const nlohmann::json& state) {
  const std::string temporary = file + ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc);
    out << nlohmann::json{{"component", component}, {"step", step}, {"state", state}}.dump() << "\n";
    if (!out) throw std::runtime_error(temporary + ": cannot write the checkpoint");
  }
  if (std::rename(temporary.c_str(), file.c_str()) != 0) {
    throw std::runtime_error(file + ": cannot replace the checkpoint");
  }
}

std::optional<Checkpoint> readCheckpoint(const std::string& file, const std::string& component) {
  if (!fs::exists(file)) return std::nullopt;
  std::ifstream in(file);
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(file + ": not a checkpoint: " + e.what());
  }
  if (!json.is_object() || !json.contains("component") || !json.contains("step") || !json.contains("state")) {
    throw std::runtime_error(file + ": not a checkpoint: needs component, step and state");
  }
  if (json["component"] != component) {
    throw std::runtime_error(file + ": the checkpoint of '" + json["component"].dump() + "', not of '" +
                             component + "'");
  }
  return Checkpoint{json["step"].get<std::uint64_t>(), json["state"]};
}

}  // namespace flatsat::bus
