// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "bus/RecordingDigest.hpp"
#include "bus/StoredSample.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace flatsat::bus {

/// A run's recording: one SQLite file, WAL journal, every sample as its CDR
/// bytes keyed by topic, step and source. Written in transactions as the run
/// goes, so a crash loses at most the open transaction.
///
/// Created for writing, it inserts on a thread of its own: insert() only
/// queues the row, and each commit hands the queued rows to that thread.
/// SQLite's insert was the recorder's whole cost and a tenth of a composed
/// step (callgrind); the writer takes it to the other core. The
/// connection belongs to the writer while it holds batches and otherwise to
/// the caller; every other call first waits for the writer and then stores
/// the queued rows itself, so reads see every insert, in arrival order.
/// A row the writer could not store makes the next insert or commit throw.
class Recording {
 public:
  enum class Access { kCreate, kRead };
  /// How a writer journals its transactions; either way a crash of the
  /// writing process loses at most the open transaction.
  enum class Journal {
    /// Write-ahead log: other processes read while it writes (a process
    /// rig's launcher, `flatsat replay` of a live run) without holding it up.
    kWal,
    /// Rollback journal: each new page goes to the file once, not to the
    /// WAL first and again at its checkpoint (about 0.3 s of a composed
    /// day's CPU, docs/performance.md), but the writer and a reader in
    /// another process take turns. For a writer that runs alone: a
    /// composed rig. A transaction cut short by a crash is taken back by
    /// the next reader that may write the file.
    kRollback,
  };
  Recording(const std::string& path, Access access, Journal journal = Journal::kWal);
  ~Recording();
  Recording(const Recording&) = delete;
  Recording& operator=(const Recording&) = delete;

  void insert(const std::string& topic, std::uint64_t step, const std::string& source,
              std::int64_t sim_time_ns, const std::vector<std::uint8_t>& payload);
  /// Commits what was inserted since the last commit and opens a new
  /// transaction; returns once it is committed (another connection sees it).
  void commit();
  /// The same commit on the writer's thread; returns at once unless the
  /// writer is still busy with the commit before.
  void commitInBackground();
  /// commitInBackground() of the rows stamped at or before `step` only: the
  /// later ones stay queued, in their order, for the next commit. A lockstep
  /// recorder trailing the rig (bus/StepReports.hpp) holds
  /// samples of steps it has not reached yet; a crash then still leaves a
  /// recording that ends at a step boundary.
  void commitInBackgroundThrough(std::uint64_t step);
  /// Hands `observer` every row this object stores, in storage order, on
  /// the writer's thread (or the caller's, when a read settles the queue):
  /// what the recorder accumulates while the run steps (summary figures).
  /// Set before the first insert; an observer must not throw.
  void observeStored(std::function<void(const StoredSample&)> observer) { observer_ = std::move(observer); }
  /// Whether every sample in the file is one this object stored (a new file,
  /// nothing erased): then what an observer saw is the whole recording.
  bool storedEverySample() const { return digest_whole_; }
  /// As the recording closes, after its last row is stored: `value()` goes
  /// to the meta table under `key` when storedEverySample(), or the key is
  /// removed when the value is empty. What an observer accumulated then
  /// includes the rows that came after the writer's last read (the
  /// components' final health, which comes as the rig stops).
  void keepOnClose(std::string key, std::function<std::string()> value) {
    keep_on_close_key_ = std::move(key);
    keep_on_close_ = std::move(value);
  }
  void setMeta(const std::string& key, const std::string& value);
  void forgetMeta(const std::string& key);
  std::string meta(const std::string& key) const;

  /// Visits one topic's samples in step order.
  void forEach(const std::string& topic,
               const std::function<void(std::uint64_t step, const std::string& source,
                                        const std::vector<std::uint8_t>& payload)>& visit) const;
  /// Visits the stamps of one topic's samples in the order the recorder
  /// received them (what an exclusive-ownership reader saw: a bridge stamps
  /// its samples with its own, possibly older, step), without their payloads: from the (topic, source, step)
  /// index alone, where forEach(kArrival) reads the whole file.
  void forEachStamp(const std::string& topic,
                    const std::function<void(std::uint64_t step, const std::string& source)>& visit) const;
  /// Visits every sample in storage order (the order the recorder stored
  /// them in), in one pass over the file and without its index.
  void forEachStored(const std::function<void(const StoredSample&)>& visit) const;
  /// Visits every sample of every topic in step order (then topic, source),
  /// with the simulated time it was recorded at.
  void forEachSample(const std::function<void(const std::string& topic, std::uint64_t step,
                                              const std::string& source, std::int64_t sim_time_ns,
                                              const std::vector<std::uint8_t>& payload)>& visit) const;
  /// Visits the samples of one topic stamped `step` (one per source).
  void forEachAt(const std::string& topic, std::uint64_t step,
                 const std::function<void(const std::string& source,
                                          const std::vector<std::uint8_t>& payload)>& visit) const;
  /// Whether `topic` holds a sample of `source` stamped `step` with exactly
  /// these bytes: what a resumed recorder asks of every sample of the steps
  /// it checks. forEachAt() searches the (topic, source, step) index by topic
  /// alone and reads every step of the topic, so a resume's check phase went
  /// quadratic in its steps; this reads the rows of one (topic, source) for
  /// kWindowSteps steps from `step` on in one range query of the full index
  /// and answers the samples after it from them (a producer's samples come
  /// in step order). Any insert or erase drops what was read.
  bool holds(const std::string& topic, std::uint64_t step, const std::string& source,
             const std::vector<std::uint8_t>& payload) const;
  std::uint64_t count(const std::string& topic) const;
  /// The highest step recorded on `topic`; nothing when it has no sample.
  std::optional<std::uint64_t> lastStep(const std::string& topic) const;
  /// Removes every sample stamped after `step` (a resumed run records them again).
  void eraseAfter(std::uint64_t step);
  /// Every recorded topic with the sources that published it.
  std::map<std::string, std::set<std::string>> topicSources() const;
  /// What one topic holds: its sample count and the span of its stamps.
  struct TopicExtent {
    std::uint64_t samples = 0;
    std::uint64_t first_step = 0, last_step = 0;
    std::int64_t first_sim_time_ns = 0, last_sim_time_ns = 0;
  };
  /// Every recorded topic's extent, in one pass over the samples.
  std::map<std::string, TopicExtent> extents() const;
  /// The recording's digest (bus/RecordingDigest.hpp), from its samples as
  /// the file holds them now: read in storage order, without a sort, and
  /// only a stream stored out of step order read again in order.
  std::string digest() const;
  /// The digest of the samples this object stored, when they are every
  /// sample the file holds: nothing when it was opened with samples in it,
  /// erased some, or stored a stream out of order.
  std::optional<std::string> storedDigest() const;
  /// Writes storedDigest() to the meta table (meta key "recording_sha256"),
  /// or removes the key when there is none: what a reader of a finished
  /// recording takes instead of digest(). The destructor does it again.
  void keepDigest();

 private:
  /// Rows queued for the writer, their text and bytes in one buffer: no
  /// allocation per row once the buffers have grown.
  struct Rows {
    struct Row {
      std::size_t topic, topic_size, source, source_size, payload, payload_size;
      std::uint64_t step;
      std::int64_t sim_time_ns;
    };
    std::vector<Row> rows;
    std::string bytes;
    void clear() {  // keeps the capacity
      rows.clear();
      bytes.clear();
    }
    void add(std::string_view topic, std::uint64_t step, std::string_view source, std::int64_t sim_time_ns,
             std::string_view payload);
    /// Adds `row` of `from` (another Rows).
    void add(const Rows& from, const Row& row) {
      const char* b = from.bytes.data();
      add({b + row.topic, row.topic_size}, row.step, {b + row.source, row.source_size}, row.sim_time_ns,
          {b + row.payload, row.payload_size});
    }
  };
  /// holds()'s rows of one (topic, source) stamped first..end - 1, in step order.
  struct Window {
    std::uint64_t first = 0, end = 0;
    std::vector<std::uint64_t> steps;
    std::vector<std::size_t> payload_ends;  // payload i is bytes[payload_ends[i - 1], payload_ends[i])
    std::string bytes;
    void read(sqlite3_stmt* range, std::uint64_t from);
    bool holds(std::uint64_t step, const std::vector<std::uint8_t>& payload) const;
  };
  void exec(const char* sql) const;
  bool holdsSamples() const;
  /// Before a query that reads by (topic, source, step): builds the index a
  /// new recording's writer left to its first reader (meta::kIndexDeferred),
  /// when this process may write the file; otherwise the query scans.
  void needIndex() const;
  void store(const Rows& rows) const;
  /// Takes the connection from the writer: waits until it is idle, then
  /// stores the queued rows. The lock keeps the writer idle while it is held.
  std::unique_lock<std::mutex> settle() const;
  /// Hands the queued rows to the writer (waiting while kBatchesInFlight wait for it); under lock.
  void handOver(std::unique_lock<std::mutex>& lock);
  void throwIfFailed() const;  ///< under queue_mutex_
  void writeBatches();         ///< the writer thread

  std::string path_;
  /// Of the rows store() stored, when they are the file's every row (digest_whole_).
  mutable StreamDigests stored_digest_;
  bool digest_whole_ = false;
  std::function<void(const StoredSample&)> observer_;
  std::string keep_on_close_key_;
  std::function<std::string()> keep_on_close_;
  mutable bool index_checked_ = false;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* insert_ = nullptr;       // one row
  sqlite3_stmt* insert_many_ = nullptr;  // kRowsPerInsert rows
  mutable sqlite3_stmt* range_ = nullptr;  // holds()' range query, prepared at its first call
  /// Steps of one (topic, source) a range query of holds() reads: the
  /// query's cost shared by 64 samples (docs/performance.md, "A resume's
  /// check"). The default rig's windows hold about 170 kB.
  static constexpr std::uint64_t kWindowSteps = 64;
  /// topic -> source -> rows, under queue_mutex_; std::less<>: found without a copy of the names.
  mutable std::map<std::string, std::map<std::string, Window, std::less<>>, std::less<>> windows_;
  /// Rows per INSERT of a batch: SQLite's work per statement (its virtual
  /// machine's start, the reset) is paid once for them (docs/performance.md).
  static constexpr int kRowsPerInsert = 16;
  bool writing_ = false;
  mutable std::mutex queue_mutex_;
  mutable std::condition_variable writer_changed_;
  /// A commit that makes SQLite checkpoint its WAL takes the writer tens of
  /// milliseconds: so many batches may wait for it before a commit waits.
  static constexpr std::size_t kBatchesInFlight = 16;
  mutable Rows queued_;         // inserted, not yet handed to the writer
  std::deque<Rows> handed_;     // the writer's, oldest (the one it writes) first
  std::vector<Rows> spare_;     // written batches, their buffers kept for reuse
  bool closing_ = false;
  std::string failure_;  // why the writer could not store a batch
  std::thread writer_;
};

}  // namespace flatsat::bus
