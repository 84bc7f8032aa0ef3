// SPDX-License-Identifier: Apache-2.0
#pragma once
// Reads a recording's rows with plain SQL, independently of bus::Recording,
// so that tests compare recordings without trusting the code under test.
#include <sqlite3.h>

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace flatsat::test {

/// (step, source) -> CDR payload bytes of one topic.
using TopicRows = std::map<std::pair<std::uint64_t, std::string>, std::vector<std::uint8_t>>;

inline TopicRows recordedRows(const std::string& path, const std::string& topic) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    throw std::runtime_error(path + ": cannot open");
  }
  sqlite3_stmt* stmt = nullptr;
  if (sqlite3_prepare_v2(db, "SELECT step, source, payload FROM samples WHERE topic = ?", -1, &stmt,
                         nullptr) != SQLITE_OK) {
    const std::string reason = sqlite3_errmsg(db);
    sqlite3_close(db);
    throw std::runtime_error(path + ": " + reason);
  }
  sqlite3_bind_text(stmt, 1, topic.c_str(), -1, SQLITE_TRANSIENT);
  TopicRows rows;
  while (sqlite3_step(stmt) == SQLITE_ROW) {
    const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(stmt, 2));
    rows[{static_cast<std::uint64_t>(sqlite3_column_int64(stmt, 0)),
          reinterpret_cast<const char*>(sqlite3_column_text(stmt, 1))}] =
        std::vector<std::uint8_t>(data, data + sqlite3_column_bytes(stmt, 2));
  }
  sqlite3_finalize(stmt);
  sqlite3_close(db);
  return rows;
}

}  // namespace flatsat::test
