// SPDX-License-Identifier: Apache-2.0
#pragma once
// Reads the CSV files the rig writes (mc.csv, `flatsat export --csv`): a
// header row, then one row per record, cells without quoting.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace flatsat::test {

struct Csv {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
};

/// @throws std::runtime_error naming the file and line when a row's cells do not match the header.
inline Csv readCsv(const std::filesystem::path& file) {
  Csv csv;
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot open");
  auto split = [](const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream stream(line);
    for (std::string cell; std::getline(stream, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    return cells;
  };
  std::string line;
  std::getline(in, line);
  csv.header = split(line);
  for (int number = 2; std::getline(in, line); ++number) {
    const auto cells = split(line);
    if (cells.size() != csv.header.size()) {
      throw std::runtime_error(file.string() + ":" + std::to_string(number) + ": " + std::to_string(cells.size()) +
                               " cells, the header has " + std::to_string(csv.header.size()));
    }
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < cells.size(); ++i) row[csv.header[i]] = cells[i];
    csv.rows.push_back(row);
  }
  return csv;
}

}  // namespace flatsat::test
