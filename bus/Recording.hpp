// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace flatsat::bus {

/// A run's recording: one SQLite file, WAL journal, every sample as its CDR
/// bytes keyed by topic, step and source. Written in transactions as the run
/// goes, so a crash loses at most the open transaction.
class Recording {
 public:
  enum class Access { kCreate, kRead };
  Recording(const std::string& path, Access access);
  ~Recording();
  Recording(const Recording&) = delete;
  Recording& operator=(const Recording&) = delete;

  void insert(const std::string& topic, std::uint64_t step, const std::string& source,
              std::int64_t sim_time_ns, const std::vector<std::uint8_t>& payload);
  /// Commits what was inserted since the last commit and opens a new transaction.
  void commit();
  void setMeta(const std::string& key, const std::string& value);
  std::string meta(const std::string& key) const;

  enum class Order { kStep, kArrival };
  /// Visits one topic's samples in step order, or in the order the recorder
  /// received them (what an exclusive-ownership reader saw: a bridge stamps
  /// its samples with its own, possibly older, step).
  void forEach(const std::string& topic,
               const std::function<void(std::uint64_t step, const std::string& source,
                                        const std::vector<std::uint8_t>& payload)>& visit,
               Order order = Order::kStep) const;
  /// Visits the samples of one topic stamped `step` (one per source).
  void forEachAt(const std::string& topic, std::uint64_t step,
                 const std::function<void(const std::string& source,
                                          const std::vector<std::uint8_t>& payload)>& visit) const;
  std::uint64_t count(const std::string& topic) const;
  /// The highest step recorded on `topic`; nothing when it has no sample.
  std::optional<std::uint64_t> lastStep(const std::string& topic) const;
  /// Removes every sample stamped after `step` (a resumed run records them again).
  void eraseAfter(std::uint64_t step);
  /// Every recorded topic with the sources that published it.
  std::map<std::string, std::set<std::string>> topicSources() const;
  /// SHA-256 (hex) over every sample of every topic except `excluded`, in
  /// (topic, source, step) order: independent of arrival order and of
  /// wall-clock topics.
  std::string digest(const std::vector<std::string>& excluded) const;

 private:
  void exec(const char* sql) const;
  bool holdsSamples() const;
  std::string path_;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* insert_ = nullptr;
  bool writing_ = false;
};

}  // namespace flatsat::bus
