// SPDX-License-Identifier: Apache-2.0
#include "bus/Checkpoint.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace flatsat::bus {

namespace fs = std::filesystem;

void writeCheckpoint(const std::string& file, const std::string& component, const Checkpoint& checkpoint) {
  const std::string temporary = file + ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc);
    out << nlohmann::json{{"component", component},
                          {"step", checkpoint.step},
                          {"state", checkpoint.state},
                          {"claimed", checkpoint.claimed}}
               .dump()
        << "\n";
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
  for (const char* key : {"component", "step", "state", "claimed"}) {
    if (!json.is_object() || !json.contains(key)) {
      throw std::runtime_error(file + ": not a checkpoint: needs component, step, state and claimed");
    }
  }
  if (json["component"] != component) {
    throw std::runtime_error(file + ": the checkpoint of '" + json["component"].dump() + "', not of '" +
                             component + "'");
  }
  try {
    Checkpoint checkpoint{json["step"].get<std::uint64_t>(), json["state"], json["claimed"].get<std::uint64_t>()};
    if (checkpoint.claimed < checkpoint.step) throw std::runtime_error("claimed is before step");
    return checkpoint;
  } catch (const std::exception& e) {
    throw std::runtime_error(file + ": not a checkpoint: " + e.what());
  }
}

}  // namespace flatsat::bus
