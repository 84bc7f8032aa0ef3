// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <string>

#include <nlohmann/json.hpp>

namespace flatsat::rig {

/// Writes FILE.partial and renames it over FILE once it is whole and flushed:
/// a reader on another node sees the old file or the new one, never half.
/// Throws std::runtime_error naming the file when it cannot be written.
void writeJsonAtomically(const std::string& file, const nlohmann::ordered_json& content);

/// Reads a whole JSON file; throws std::runtime_error naming the file and,
/// for bad JSON, the parser's reason. `unreadable_hint` is added to the
/// message when the file cannot be opened at all.
nlohmann::ordered_json readJsonFile(const std::string& file, const std::string& unreadable_hint = "");

}  // namespace flatsat::rig
