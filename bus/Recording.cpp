// SPDX-License-Identifier: Apache-2.0
#include "bus/Recording.hpp"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include <sqlite3.h>

#include "bus/RecordingMeta.hpp"

namespace flatsat::bus {

namespace {

/// A 64 MiB page cache (SQLite's default is 2 MiB): for the reads in index
/// order and for the index's sort at close.
constexpr const char* kLargeCache = "PRAGMA cache_size=-65536";
constexpr const char* kCreateIndex = "CREATE INDEX IF NOT EXISTS samples_by_topic ON samples (topic, source, step)";

struct Statement {
  Statement(sqlite3* db, const std::string& sql, const std::string& path) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt, nullptr) != SQLITE_OK) {
      throw std::runtime_error(path + ": " + sqlite3_errmsg(db));
    }
  }
  ~Statement() { sqlite3_finalize(stmt); }
  sqlite3_stmt* stmt = nullptr;
};

std::vector<std::uint8_t> blob(sqlite3_stmt* stmt, int column) {
  const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(stmt, column));
  return {data, data + sqlite3_column_bytes(stmt, column)};
}

std::string text(sqlite3_stmt* stmt, int column) {
  const auto* data = sqlite3_column_text(stmt, column);
  return data == nullptr ? "" : reinterpret_cast<const char*>(data);
}

/// Valid until the statement steps on.
std::string_view textView(sqlite3_stmt* stmt, int column) {
  const auto* data = reinterpret_cast<const char*>(sqlite3_column_text(stmt, column));
  return data == nullptr ? std::string_view() : std::string_view(data, sqlite3_column_bytes(stmt, column));
}

/// What an earlier writer kept of other samples: its digest, its figures,
/// and its word that the index is left to a reader.
const std::string kForgetKept = std::string("DELETE FROM meta WHERE key IN ('") + meta::kDigest + "', '" +
                                meta::kFigures + "', '" + meta::kIndexDeferred + "')";
const std::string kDeferIndex =
    std::string("INSERT OR REPLACE INTO meta VALUES ('") + meta::kIndexDeferred + "', '1')";
const std::string kForgetDeferral = std::string("DELETE FROM meta WHERE key = '") + meta::kIndexDeferred + "'";

/// Runs `sql` on a connection of its own that may write the file: a reader's
/// errand (it opened the file read-only). False when this process may not
/// write the file or `sql` failed, which is then rolled back.
bool execWithWriteAccess(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  bool done = false;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX, nullptr) == SQLITE_OK) {
    sqlite3_busy_timeout(db, 10'000);
    done = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr) == SQLITE_OK;
    if (!done) sqlite3_exec(db, "ROLLBACK", nullptr, nullptr, nullptr);
  }
  sqlite3_close(db);
  return done;
}

/// A rollback-journal writer killed in a transaction leaves its journal
/// "hot": the pages it changed, to be put back before anyone reads. SQLite
/// does that at the next read, but only on a connection that may write (a
/// read-only one fails, "attempt to write a readonly database"), so a reader
/// that may write the file takes it back first. While the writer lives its
/// journal is not hot, and this reads and changes nothing.
void takeBackInterruptedTransaction(const std::string& path) {
  std::error_code error;
  if (std::filesystem::file_size(path + "-journal", error) == 0 || error) return;
  execWithWriteAccess(path, "SELECT count(*) FROM sqlite_master");
}

/// SQLite counts its allocations under a global mutex unless told not to
/// before its first use; the writer allocates for every row.
void countNoAllocations() {
  static std::once_flag once;
  std::call_once(once, [] { sqlite3_config(SQLITE_CONFIG_MEMSTATUS, 0); });
}

}  // namespace

Recording::Recording(const std::string& path, Access access, Journal journal) : path_(path) {
  countNoAllocations();
  if (access == Access::kRead) takeBackInterruptedTransaction(path);
  // No SQLite mutexes: the connection has one user at a time (see settle()).
  const int flags = SQLITE_OPEN_NOMUTEX | (access == Access::kCreate ? SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE
                                                                     : SQLITE_OPEN_READONLY);
  if (sqlite3_open_v2(path.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
    const std::string reason = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw std::runtime_error(path + ": cannot open recording: " + reason);
  }
  // A reader of a recording still being written (a launcher on another host,
  // `flatsat replay` of a live run) can find it busy for a moment in WAL mode.
  sqlite3_busy_timeout(db_, 10'000);
  // A summary reads the samples in index order, not in the rowid order they
  // were written in: through a small page cache every row costs a pread.
  // Mapping the file and a 64 MiB cache make those reads memory reads.
  if (access == Access::kRead) {
    exec("PRAGMA mmap_size=1073741824");
    exec(kLargeCache);
    return;
  }
  writing_ = true;
  // 64 KiB pages (SQLite's largest; its default is 4 KiB): the writer appends
  // a page per pwrite, and with 4 KiB pages its syscalls were most of its time
  // (strace, default scenario: 71,762 pwrite calls for 200,000 steps). Only a
  // new file takes it, and only before the journal becomes WAL.
  exec("PRAGMA page_size=65536");
  // Either journal with NORMAL: a committed transaction survives a crash of
  // this process, and the file stays whole across a power cut.
  if (journal == Journal::kWal) {
    exec("PRAGMA journal_mode=WAL");
  } else {
    exec("PRAGMA journal_mode=DELETE");
    // The writer and a reader take turns: a reader holds off the writer's
    // next write to the file, the writer holds readers off from the first
    // page it writes out (its small cache full) to its commit. Either waits
    // rather than fails: the rig is late, not failed. A 64 MiB cache, which
    // would write only at the commit, cost 0.1 s more of a composed day than
    // it saved.
    sqlite3_busy_timeout(db_, 600'000);
  }
  exec("PRAGMA synchronous=NORMAL");
  exec("CREATE TABLE IF NOT EXISTS samples (topic TEXT NOT NULL, step INTEGER NOT NULL, "
       "source TEXT NOT NULL, sim_time_ns INTEGER NOT NULL, payload BLOB NOT NULL)");
  exec("CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL)");
  // The (topic, source, step) index is not kept up on every insert: that
  // upkeep was half the cost of an insert (callgrind, default scenario), and
  // kept up in a file of 64 KiB pages it rewrote them at every commit. Nor
  // is it sorted when the recording closes (1.1 s of a composed day, whose
  // summary the recorder accumulated without it): the first reader that
  // needs it builds it (needIndex). A recording that already holds samples
  // (a resumed run, whose recorder looks its samples up) gets it now.
  // Without it, as after a crash, every query still answers, by scanning.
  digest_whole_ = !holdsSamples();
  if (!digest_whole_) exec(kCreateIndex);
  exec(kForgetKept.c_str());
  // OR FAIL: a failed row does not take back the rows of its statement that
  // went in before it, so SQLite keeps no statement journal. With the
  // default (ABORT), every multi-row INSERT first copied the 64 KiB page it
  // would change into that journal, a temporary file: 82,584 writes of a
  // page in a composed day, against 9,600 for the WAL itself (strace).
  // A failed row fails the recording anyway (failure_).
  const std::string one = "INSERT OR FAIL INTO samples VALUES (?, ?, ?, ?, ?)";
  std::string many = one;
  for (int i = 1; i < kRowsPerInsert; ++i) many += ", (?, ?, ?, ?, ?)";
  if (sqlite3_prepare_v2(db_, one.c_str(), -1, &insert_, nullptr) != SQLITE_OK ||
      sqlite3_prepare_v2(db_, many.c_str(), -1, &insert_many_, nullptr) != SQLITE_OK) {
    throw std::runtime_error(path + ": " + sqlite3_errmsg(db_));
  }
  exec("BEGIN");
  writer_ = std::thread([this] { writeBatches(); });
}

Recording::~Recording() {
  if (writing_) {
    {
      std::unique_lock lock(queue_mutex_);
      try {
        handOver(lock);
      } catch (const std::exception&) {  // the writer failed before: what it stored is committed
      }
      closing_ = true;
      writer_changed_.notify_all();
    }
    writer_.join();  // after the batch handed over last
    try {
      keepDigest();
    } catch (const std::exception&) {  // a reader computes the digest again
    }
    if (keep_on_close_) {
      try {
        const std::string value = digest_whole_ ? keep_on_close_() : std::string();
        if (value.empty()) {
          forgetMeta(keep_on_close_key_);
        } else {
          setMeta(keep_on_close_key_, value);
        }
      } catch (const std::exception&) {  // the key stays as the writer's last read left it
      }
    }
    if (digest_whole_) sqlite3_exec(db_, kDeferIndex.c_str(), nullptr, nullptr, nullptr);
    sqlite3_exec(db_, "COMMIT", nullptr, nullptr, nullptr);
  }
  sqlite3_finalize(insert_);
  sqlite3_finalize(insert_many_);
  sqlite3_finalize(range_);
  sqlite3_close(db_);
}

void Recording::writeBatches() {
  std::unique_lock lock(queue_mutex_);
  for (;;) {
    writer_changed_.wait(lock, [this] { return !handed_.empty() || closing_; });
    if (handed_.empty()) return;
    Rows& batch = handed_.front();  // stays put while handOver() appends behind it
    lock.unlock();
    std::string failure;
    try {
      store(batch);
      exec("COMMIT");
      exec("BEGIN");
    } catch (const std::exception& e) {
      failure = e.what();
    }
    batch.clear();
    lock.lock();
    if (failure_.empty()) failure_ = failure;
    spare_.push_back(std::move(batch));
    handed_.pop_front();
    writer_changed_.notify_all();
  }
}

void Recording::throwIfFailed() const {
  if (!failure_.empty()) throw std::runtime_error(failure_);
}

void Recording::handOver(std::unique_lock<std::mutex>& lock) {
  writer_changed_.wait(lock, [this] { return handed_.size() < kBatchesInFlight; });
  throwIfFailed();
  handed_.push_back(std::move(queued_));
  queued_ = Rows{};
  if (!spare_.empty()) {
    queued_ = std::move(spare_.back());
    spare_.pop_back();
  }
  writer_changed_.notify_all();
}

std::unique_lock<std::mutex> Recording::settle() const {
  std::unique_lock lock(queue_mutex_);
  writer_changed_.wait(lock, [this] { return handed_.empty(); });
  if (!queued_.rows.empty()) {
    store(queued_);
    queued_.clear();
  }
  return lock;
}

bool Recording::holdsSamples() const {
  const auto lock = settle();
  Statement s(db_, "SELECT 1 FROM samples LIMIT 1", path_);
  return sqlite3_step(s.stmt) == SQLITE_ROW;
}

void Recording::exec(const char* sql) const {
  char* error = nullptr;
  if (sqlite3_exec(db_, sql, nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string reason = error ? error : "unknown error";
    sqlite3_free(error);
    throw std::runtime_error(path_ + ": " + sql + ": " + reason);
  }
}

void Recording::insert(const std::string& topic, std::uint64_t step, const std::string& source,
                       std::int64_t sim_time_ns, const std::vector<std::uint8_t>& payload) {
  if (!writing_) throw std::logic_error(path_ + ": opened for reading, not for inserting");
  std::lock_guard lock(queue_mutex_);
  throwIfFailed();
  windows_.clear();  // holds() reads the rows again: this one may be in a window
  queued_.add(topic, step, source, sim_time_ns,
              {reinterpret_cast<const char*>(payload.data()), payload.size()});
}

void Recording::Rows::add(std::string_view topic, std::uint64_t step, std::string_view source,
                          std::int64_t sim_time_ns, std::string_view payload) {
  auto append = [this](std::string_view data) {
    const std::size_t at = bytes.size();
    bytes.append(data);
    return at;
  };
  const std::size_t topic_at = append(topic);
  const std::size_t source_at = append(source);
  const std::size_t payload_at = append(payload);
  rows.push_back({topic_at, topic.size(), source_at, source.size(), payload_at, payload.size(), step, sim_time_ns});
}

void Recording::store(const Rows& rows) const {
  // SQLITE_STATIC: rows.bytes outlives each sqlite3_step, so SQLite copies nothing.
  const char* bytes = rows.bytes.data();
  const auto bind = [bytes](sqlite3_stmt* insert, int first, const Rows::Row& row) {
    sqlite3_bind_text(insert, first + 1, bytes + row.topic, static_cast<int>(row.topic_size), SQLITE_STATIC);
    sqlite3_bind_int64(insert, first + 2, static_cast<sqlite3_int64>(row.step));
    sqlite3_bind_text(insert, first + 3, bytes + row.source, static_cast<int>(row.source_size),
                      SQLITE_STATIC);
    sqlite3_bind_int64(insert, first + 4, row.sim_time_ns);
    sqlite3_bind_blob(insert, first + 5, bytes + row.payload, static_cast<int>(row.payload_size),
                      SQLITE_STATIC);
  };
  if (observer_) {
    for (const Rows::Row& row : rows.rows) {
      observer_({{bytes + row.topic, row.topic_size},
                 row.step,
                 {bytes + row.source, row.source_size},
                 row.sim_time_ns,
                 reinterpret_cast<const std::uint8_t*>(bytes + row.payload),
                 row.payload_size});
    }
  }
  if (digest_whole_) {
    for (const Rows::Row& row : rows.rows) {
      const std::string_view topic(bytes + row.topic, row.topic_size);
      const auto* payload = reinterpret_cast<const std::uint8_t*>(bytes + row.payload);
      if (outsideDigest(topic, payload, row.payload_size)) continue;
      stored_digest_.add(topic, {bytes + row.source, row.source_size}, row.step, payload, row.payload_size);
    }
  }
  const auto run = [this](sqlite3_stmt* insert) {
    const int rc = sqlite3_step(insert);
    sqlite3_reset(insert);
    if (rc != SQLITE_DONE) throw std::runtime_error(path_ + ": insert failed: " + sqlite3_errmsg(db_));
  };
  // The rows of a multi-row VALUES are inserted in their order: the rowids,
  // the arrival order forEach(kArrival) reads, are as one row at a time.
  std::size_t i = 0;
  for (; i + kRowsPerInsert <= rows.rows.size(); i += kRowsPerInsert) {
    for (int j = 0; j < kRowsPerInsert; ++j) bind(insert_many_, 5 * j, rows.rows[i + j]);
    run(insert_many_);
  }
  for (; i < rows.rows.size(); ++i) {
    bind(insert_, 0, rows.rows[i]);
    run(insert_);
  }
}

void Recording::commit() {
  std::unique_lock lock(queue_mutex_);
  handOver(lock);
  writer_changed_.wait(lock, [this] { return handed_.empty(); });
  throwIfFailed();
}

void Recording::commitInBackground() {
  std::unique_lock lock(queue_mutex_);
  handOver(lock);
}

void Recording::commitInBackgroundThrough(std::uint64_t step) {
  std::unique_lock lock(queue_mutex_);
  // Copied out before the hand-over: the writer clears a batch it stored
  // without the lock. The rows kept point into bytes that stay as they are.
  Rows later;
  std::size_t kept = 0;
  for (const Rows::Row& row : queued_.rows) {
    if (row.step <= step) {
      queued_.rows[kept++] = row;
    } else {
      later.add(queued_, row);
    }
  }
  queued_.rows.resize(kept);
  handOver(lock);
  for (const Rows::Row& row : later.rows) queued_.add(later, row);
}

void Recording::setMeta(const std::string& key, const std::string& value) {
  const auto lock = settle();
  Statement s(db_, "INSERT OR REPLACE INTO meta VALUES (?, ?)", path_);
  sqlite3_bind_text(s.stmt, 1, key.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s.stmt, 2, value.c_str(), -1, SQLITE_TRANSIENT);
  if (sqlite3_step(s.stmt) != SQLITE_DONE) {
    throw std::runtime_error(path_ + ": cannot write meta " + key + ": " + sqlite3_errmsg(db_));
  }
}

std::string Recording::meta(const std::string& key) const {
  const auto lock = settle();
  Statement s(db_, "SELECT value FROM meta WHERE key = ?", path_);
  sqlite3_bind_text(s.stmt, 1, key.c_str(), -1, SQLITE_TRANSIENT);
  return sqlite3_step(s.stmt) == SQLITE_ROW ? text(s.stmt, 0) : "";
}

void Recording::forEach(
    const std::string& topic,
    const std::function<void(std::uint64_t, const std::string&, const std::vector<std::uint8_t>&)>& visit) const {
  needIndex();
  const auto lock = settle();
  Statement s(db_, "SELECT step, source, payload FROM samples WHERE topic = ? ORDER BY step, source", path_);
  sqlite3_bind_text(s.stmt, 1, topic.c_str(), -1, SQLITE_TRANSIENT);
  while (sqlite3_step(s.stmt) == SQLITE_ROW) {
    visit(static_cast<std::uint64_t>(sqlite3_column_int64(s.stmt, 0)), text(s.stmt, 1), blob(s.stmt, 2));
  }
}

void Recording::forEachStamp(const std::string& topic,
                             const std::function<void(std::uint64_t, const std::string&)>& visit) const {
  needIndex();
  const auto lock = settle();
  // Rows are inserted as samples arrive, so rowid is the arrival order.
  Statement s(db_, "SELECT step, source FROM samples WHERE topic = ? ORDER BY rowid", path_);
  sqlite3_bind_text(s.stmt, 1, topic.c_str(), -1, SQLITE_TRANSIENT);
  while (sqlite3_step(s.stmt) == SQLITE_ROW) {
    visit(static_cast<std::uint64_t>(sqlite3_column_int64(s.stmt, 0)), text(s.stmt, 1));
  }
}

void Recording::needIndex() const {
  if (writing_ || index_checked_) return;
  index_checked_ = true;
  if (meta(meta::kIndexDeferred).empty()) return;
  // The sort in memory, not through temporary files. Where it cannot be
  // built (read-only after all) the queries scan.
  execWithWriteAccess(path_, std::string("PRAGMA temp_store=MEMORY; ") + kLargeCache + "; BEGIN IMMEDIATE; " +
                                 kCreateIndex + "; " + kForgetDeferral + "; COMMIT");
}

void Recording::forEachStored(const std::function<void(const StoredSample&)>& visit) const {
  const auto lock = settle();
  Statement s(db_, "SELECT topic, step, source, sim_time_ns, payload FROM samples ORDER BY rowid", path_);
  while (sqlite3_step(s.stmt) == SQLITE_ROW) {
    visit({textView(s.stmt, 0), static_cast<std::uint64_t>(sqlite3_column_int64(s.stmt, 1)), textView(s.stmt, 2),
           sqlite3_column_int64(s.stmt, 3), static_cast<const std::uint8_t*>(sqlite3_column_blob(s.stmt, 4)),
           static_cast<std::size_t>(sqlite3_column_bytes(s.stmt, 4))});
  }
}

void Recording::forEachSample(
    const std::function<void(const std::string&, std::uint64_t, const std::string&, std::int64_t,
                             const std::vector<std::uint8_t>&)>& visit) const {
  const auto lock = settle();
  Statement s(db_, "SELECT topic, step, source, sim_time_ns, payload FROM samples ORDER BY step, topic, source",
              path_);
  while (sqlite3_step(s.stmt) == SQLITE_ROW) {
    visit(text(s.stmt, 0), static_cast<std::uint64_t>(sqlite3_column_int64(s.stmt, 1)), text(s.stmt, 2),
          sqlite3_column_int64(s.stmt, 3), blob(s.stmt, 4));
  }
}

void Recording::forEachAt(
    const std::string& topic, std::uint64_t step,
    const std::function<void(const std::string&, const std::vector<std::uint8_t>&)>& visit) const {
  needIndex();
  const auto lock = settle();
  Statement s(db_, "SELECT source, payload FROM samples WHERE topic = ? AND step = ? ORDER BY source",
              path_);
  sqlite3_bind_text(s.stmt, 1, topic.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_int64(s.stmt, 2, static_cast<sqlite3_int64>(step));
  while (sqlite3_step(s.stmt) == SQLITE_ROW) visit(text(s.stmt, 0), blob(s.stmt, 1));
}

bool Recording::holds(const std::string& topic, std::uint64_t step, const std::string& source,
                      const std::vector<std::uint8_t>& payload) const {
  const auto lock = settle();
  if (range_ == nullptr &&
      sqlite3_prepare_v2(db_,
                         "SELECT step, payload FROM samples WHERE topic = ? AND source = ? AND step >= ? AND step < ? "
                         "ORDER BY step",
                         -1, &range_, nullptr) != SQLITE_OK) {
    throw std::runtime_error(path_ + ": " + sqlite3_errmsg(db_));
  }
  Window& window = windows_[topic][source];
  if (step < window.first || step >= window.end) {
    // SQLITE_STATIC: the names outlive the query, which read() runs to its end.
    sqlite3_bind_text(range_, 1, topic.data(), static_cast<int>(topic.size()), SQLITE_STATIC);
    sqlite3_bind_text(range_, 2, source.data(), static_cast<int>(source.size()), SQLITE_STATIC);
    window.read(range_, step);
  }
  return window.holds(step, payload);
}

void Recording::Window::read(sqlite3_stmt* range, std::uint64_t from) {
  first = from;
  end = from + kWindowSteps;
  steps.clear();
  payload_ends.clear();
  bytes.clear();
  sqlite3_bind_int64(range, 3, static_cast<sqlite3_int64>(first));
  sqlite3_bind_int64(range, 4, static_cast<sqlite3_int64>(end));
  while (sqlite3_step(range) == SQLITE_ROW) {
    steps.push_back(static_cast<std::uint64_t>(sqlite3_column_int64(range, 0)));
    const auto size = static_cast<std::size_t>(sqlite3_column_bytes(range, 1));
    if (size > 0) bytes.append(static_cast<const char*>(sqlite3_column_blob(range, 1)), size);
    payload_ends.push_back(bytes.size());
  }
  sqlite3_reset(range);
}

bool Recording::Window::holds(std::uint64_t step, const std::vector<std::uint8_t>& payload) const {
  // A key stored twice (none should be) matches when either copy does.
  for (auto i = static_cast<std::size_t>(std::lower_bound(steps.begin(), steps.end(), step) - steps.begin());
       i < steps.size() && steps[i] == step; ++i) {
    const std::size_t begin = i == 0 ? 0 : payload_ends[i - 1];
    if (payload_ends[i] - begin == payload.size() &&
        std::equal(payload.begin(), payload.end(), reinterpret_cast<const std::uint8_t*>(bytes.data()) + begin)) {
      return true;
    }
  }
  return false;
}

std::map<std::string, std::set<std::string>> Recording::topicSources() const {
  needIndex();
  const auto lock = settle();
  Statement s(db_, "SELECT DISTINCT topic, source FROM samples", path_);
  std::map<std::string, std::set<std::string>> out;
  while (sqlite3_step(s.stmt) == SQLITE_ROW) out[text(s.stmt, 0)].insert(text(s.stmt, 1));
  return out;
}

std::uint64_t Recording::count(const std::string& topic) const {
  needIndex();
  const auto lock = settle();
  Statement s(db_, "SELECT COUNT(*) FROM samples WHERE topic = ?", path_);
  sqlite3_bind_text(s.stmt, 1, topic.c_str(), -1, SQLITE_TRANSIENT);
  return sqlite3_step(s.stmt) == SQLITE_ROW ? static_cast<std::uint64_t>(sqlite3_column_int64(s.stmt, 0)) : 0;
}

std::map<std::string, Recording::TopicExtent> Recording::extents() const {
  needIndex();
  const auto lock = settle();
  Statement s(db_,
              "SELECT topic, COUNT(*), MIN(step), MAX(step), MIN(sim_time_ns), MAX(sim_time_ns) FROM samples "
              "GROUP BY topic",
              path_);
  std::map<std::string, TopicExtent> extents;
  while (sqlite3_step(s.stmt) == SQLITE_ROW) {
    auto& e = extents[reinterpret_cast<const char*>(sqlite3_column_text(s.stmt, 0))];
    e.samples = static_cast<std::uint64_t>(sqlite3_column_int64(s.stmt, 1));
    e.first_step = static_cast<std::uint64_t>(sqlite3_column_int64(s.stmt, 2));
    e.last_step = static_cast<std::uint64_t>(sqlite3_column_int64(s.stmt, 3));
    e.first_sim_time_ns = sqlite3_column_int64(s.stmt, 4);
    e.last_sim_time_ns = sqlite3_column_int64(s.stmt, 5);
  }
  return extents;
}

std::optional<std::uint64_t> Recording::lastStep(const std::string& topic) const {
  needIndex();
  const auto lock = settle();
  Statement s(db_, "SELECT MAX(step) FROM samples WHERE topic = ?", path_);
  sqlite3_bind_text(s.stmt, 1, topic.c_str(), -1, SQLITE_TRANSIENT);
  if (sqlite3_step(s.stmt) != SQLITE_ROW || sqlite3_column_type(s.stmt, 0) == SQLITE_NULL) return std::nullopt;
  return static_cast<std::uint64_t>(sqlite3_column_int64(s.stmt, 0));
}

void Recording::eraseAfter(std::uint64_t step) {
  const auto lock = settle();
  windows_.clear();
  digest_whole_ = false;
  Statement s(db_, "DELETE FROM samples WHERE step > ?", path_);
  sqlite3_bind_int64(s.stmt, 1, static_cast<sqlite3_int64>(step));
  if (sqlite3_step(s.stmt) != SQLITE_DONE) {
    throw std::runtime_error(path_ + ": cannot erase the steps after " + std::to_string(step) + ": " +
                             sqlite3_errmsg(db_));
  }
}

std::string Recording::digest() const {
  const auto lock = settle();
  StreamDigests digests;
  {
    Statement s(db_, "SELECT topic, source, step, payload FROM samples ORDER BY rowid", path_);
    while (sqlite3_step(s.stmt) == SQLITE_ROW) {
      const std::string_view topic = textView(s.stmt, 0);
      const auto* payload = static_cast<const std::uint8_t*>(sqlite3_column_blob(s.stmt, 3));
      const auto size = static_cast<std::size_t>(sqlite3_column_bytes(s.stmt, 3));
      if (outsideDigest(topic, payload, size)) continue;
      digests.add(topic, textView(s.stmt, 1), static_cast<std::uint64_t>(sqlite3_column_int64(s.stmt, 2)), payload,
                  size);
    }
  }
  for (const auto& [topic, source] : digests.unordered()) {
    digests.restartStream(topic, source);
    Statement s(db_, "SELECT step, payload FROM samples WHERE topic = ? AND source = ? ORDER BY step, payload", path_);
    sqlite3_bind_text(s.stmt, 1, topic.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(s.stmt, 2, source.c_str(), -1, SQLITE_TRANSIENT);
    while (sqlite3_step(s.stmt) == SQLITE_ROW) {
      digests.addOrdered(topic, source, static_cast<std::uint64_t>(sqlite3_column_int64(s.stmt, 0)),
                         static_cast<const std::uint8_t*>(sqlite3_column_blob(s.stmt, 1)),
                         static_cast<std::size_t>(sqlite3_column_bytes(s.stmt, 1)));
    }
  }
  return digests.hex();
}

std::optional<std::string> Recording::storedDigest() const {
  const auto lock = settle();
  if (!digest_whole_ || !stored_digest_.unordered().empty()) return std::nullopt;
  return stored_digest_.hex();
}

void Recording::keepDigest() {
  if (const auto digest = storedDigest()) {
    setMeta(meta::kDigest, *digest);
    return;
  }
  forgetMeta(meta::kDigest);
}

void Recording::forgetMeta(const std::string& key) {
  const auto lock = settle();
  Statement s(db_, "DELETE FROM meta WHERE key = ?", path_);
  sqlite3_bind_text(s.stmt, 1, key.c_str(), -1, SQLITE_TRANSIENT);
  if (sqlite3_step(s.stmt) != SQLITE_DONE) {
    throw std::runtime_error(path_ + ": cannot remove meta " + key + ": " + sqlite3_errmsg(db_));
  }
}

}  // namespace flatsat::bus
