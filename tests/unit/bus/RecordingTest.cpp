// SPDX-License-Identifier: Apache-2.0
#include <catch2/catch.hpp>

#include <filesystem>
#include <sys/wait.h>
#include <unistd.h>

#include "bus/Recording.hpp"
#include "bus/RecordingMeta.hpp"

using flatsat::bus::Recording;
namespace meta = flatsat::bus::meta;

namespace {

enum class Order { kStep, kArrival };

/// forEach() in step order, forEachStamp() in arrival order.
std::vector<std::pair<std::uint64_t, std::string>> visit(const Recording& r, Order order) {
  std::vector<std::pair<std::uint64_t, std::string>> seen;
  const auto add = [&](std::uint64_t step, const std::string& source) { seen.emplace_back(step, source); };
  if (order == Order::kArrival) {
    r.forEachStamp("t", add);
  } else {
    r.forEach("t", [&](std::uint64_t step, const std::string& source, const std::vector<std::uint8_t>&) {
      add(step, source);
    });
  }
  return seen;
}

}  // namespace

TEST_CASE("Recording visits a topic in step order or in arrival order", "[bus][recording]") {
  const auto path = std::filesystem::temp_directory_path() /
                    ("flatsat-recording-order-" + std::to_string(::getpid()) + ".sqlite");
  std::filesystem::remove(path);
  {
    // A hand-over as the recorder sees it: the bridge's first sample carries an
    // older step than the emulator's last one.
    Recording r(path.string(), Recording::Access::kCreate);
    for (std::uint64_t step : {300, 301, 302, 303}) r.insert("t", step, "emulator", 0, {1});
    for (std::uint64_t step : {301, 303, 304}) r.insert("t", step, "bridge", 0, {2});
    r.commit();
  }
  const Recording r(path.string(), Recording::Access::kRead);
  using Seen = std::vector<std::pair<std::uint64_t, std::string>>;
  CHECK(visit(r, Order::kArrival) ==
        Seen{{300, "emulator"}, {301, "emulator"}, {302, "emulator"}, {303, "emulator"},
             {301, "bridge"}, {303, "bridge"}, {304, "bridge"}});
  CHECK(visit(r, Order::kStep) ==
        Seen{{300, "emulator"}, {301, "bridge"}, {301, "emulator"}, {302, "emulator"},
             {303, "bridge"}, {303, "emulator"}, {304, "bridge"}});
  std::filesystem::remove(path);
  std::filesystem::remove(path.string() + "-wal");
  std::filesystem::remove(path.string() + "-shm");
}

TEST_CASE("Rows stored sixteen to an INSERT keep their arrival order and their payloads", "[bus][recording]") {
  const auto path = std::filesystem::temp_directory_path() /
                    ("flatsat-recording-many-" + std::to_string(::getpid()) + ".sqlite");
  std::filesystem::remove(path);
  // 37 rows: two INSERTs of sixteen and five of one, steps out of order.
  std::vector<std::pair<std::uint64_t, std::string>> written;
  {
    Recording r(path.string(), Recording::Access::kCreate);
    for (std::uint64_t i = 0; i < 37; ++i) {
      written.emplace_back((i * 7) % 37, i % 3 == 0 ? "bridge" : "emulator");
      r.insert("t", written.back().first, written.back().second, static_cast<std::int64_t>(i),
               {static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(255 - i)});
    }
    r.commit();
  }
  const Recording r(path.string(), Recording::Access::kRead);
  CHECK(visit(r, Order::kArrival) == written);
  std::size_t matching = 0;
  r.forEach("t", [&](std::uint64_t step, const std::string&, const std::vector<std::uint8_t>& payload) {
    const std::uint64_t i = (step * 16) % 37;  // 16 = 7⁻¹ mod 37
    if (payload ==
        std::vector<std::uint8_t>{static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(255 - i)}) {
      ++matching;
    }
  });
  CHECK(matching == 37);
  std::filesystem::remove(path);
  std::filesystem::remove(path.string() + "-wal");
  std::filesystem::remove(path.string() + "-shm");
}

TEST_CASE("Recording finds a topic's last step and erases what came after a step", "[bus][recording]") {
  const auto path = std::filesystem::temp_directory_path() /
                    ("flatsat-recording-erase-" + std::to_string(::getpid()) + ".sqlite");
  std::filesystem::remove(path);
  {
    Recording r(path.string(), Recording::Access::kCreate);
    for (std::uint64_t step = 0; step < 10; ++step) r.insert("a", step, "x", 0, {1});
    for (std::uint64_t step = 0; step < 10; step += 5) r.insert("b", step, "y", 0, {2});
    CHECK(r.lastStep("a") == 9u);
    CHECK(r.lastStep("b") == 5u);
    CHECK_FALSE(r.lastStep("c").has_value());
    r.eraseAfter(6);
    r.commit();
  }
  const Recording r(path.string(), Recording::Access::kRead);
  CHECK(r.count("a") == 7);  // steps 0..6
  CHECK(r.count("b") == 2);
  CHECK(r.lastStep("a") == 6u);
  std::filesystem::remove(path);
  std::filesystem::remove(path.string() + "-wal");
  std::filesystem::remove(path.string() + "-shm");
}

TEST_CASE("A recording holds a sample only with its topic, source, step and every byte", "[bus][recording]") {
  const auto path = std::filesystem::temp_directory_path() /
                    ("flatsat-recording-holds-" + std::to_string(::getpid()) + ".sqlite");
  std::filesystem::remove(path);
  {
    Recording first(path.string(), Recording::Access::kCreate);
    for (std::uint64_t step = 0; step < 100; ++step) {
      first.insert("t", step, "x", 0, {1, static_cast<std::uint8_t>(step)});
      first.insert("t", step, "y", 0, {2, static_cast<std::uint8_t>(step)});
    }
    first.insert("e", 7, "x", 0, {});
    first.commit();
  }
  {
    // Reopened for writing, as a resumed recorder opens it (with its index), and
    // asked both before and after rows queued since.
    Recording r(path.string(), Recording::Access::kCreate);
    CHECK(r.holds("t", 42, "x", {1, 42}));
    CHECK(r.holds("t", 42, "y", {2, 42}));
    CHECK_FALSE(r.holds("t", 42, "x", {2, 42}));     // another source's bytes
    CHECK_FALSE(r.holds("t", 42, "x", {1, 43}));     // one byte off
    CHECK_FALSE(r.holds("t", 42, "x", {1, 42, 0}));  // one byte more
    CHECK_FALSE(r.holds("t", 42, "x", {1}));         // one byte less
    CHECK_FALSE(r.holds("t", 100, "x", {1, 100}));   // a step not recorded
    CHECK_FALSE(r.holds("u", 42, "x", {1, 42}));     // another topic
    CHECK(r.holds("e", 7, "x", {}));
    CHECK_FALSE(r.holds("e", 7, "x", {0}));
    r.insert("t", 100, "x", 0, {1, 100});
    CHECK(r.holds("t", 100, "x", {1, 100}));
    r.commit();
    CHECK(r.holds("t", 99, "y", {2, 99}));
  }
  std::filesystem::remove(path);
  std::filesystem::remove(path.string() + "-wal");
  std::filesystem::remove(path.string() + "-shm");
}

TEST_CASE("A recording still open (as after a crash) answers without its index, as it does closed",
          "[bus][recording]") {
  const auto path = std::filesystem::temp_directory_path() /
                    ("flatsat-recording-index-" + std::to_string(::getpid()) + ".sqlite");
  std::filesystem::remove(path);
  std::string digest_open;
  std::vector<std::pair<std::uint64_t, std::string>> seen_open;
  {
    Recording writer(path.string(), Recording::Access::kCreate);
    // Out of step order and interleaved, as samples arrive.
    for (std::uint64_t step : {3u, 1u, 2u, 0u}) {
      writer.insert("t", step, "b", 0, {static_cast<std::uint8_t>(step)});
      writer.insert("t", step, "a", 0, {static_cast<std::uint8_t>(10 + step)});
      writer.insert("u", step, "a", 0, {7});
    }
    writer.commit();
    const Recording reader(path.string(), Recording::Access::kRead);
    digest_open = reader.digest();
    seen_open = visit(reader, Order::kStep);
    CHECK(reader.count("t") == 8);
    CHECK(reader.lastStep("u") == 3u);
  }
  const Recording closed(path.string(), Recording::Access::kRead);
  CHECK(closed.digest() == digest_open);
  CHECK(visit(closed, Order::kStep) == seen_open);
  CHECK(seen_open.front() == std::make_pair(std::uint64_t{0}, std::string("a")));
  CHECK(seen_open.back() == std::make_pair(std::uint64_t{3}, std::string("b")));
  std::filesystem::remove(path);
  std::filesystem::remove(path.string() + "-wal");
  std::filesystem::remove(path.string() + "-shm");
}

TEST_CASE("A new recording's index is built by its first reader that needs it, once", "[bus][recording]") {
  const auto path = std::filesystem::temp_directory_path() /
                    ("flatsat-recording-deferred-" + std::to_string(::getpid()) + ".sqlite");
  std::filesystem::remove(path);
  {
    Recording writer(path.string(), Recording::Access::kCreate);
    for (std::uint64_t step = 0; step < 50; ++step) writer.insert("t", 49 - step, "a", 0, {1});
  }
  {
    const Recording reader(path.string(), Recording::Access::kRead);
    CHECK(reader.meta(meta::kIndexDeferred) == "1");  // closed without the index's sort
    CHECK(reader.digest().size() == 64);              // read in storage order: no index needed
    CHECK(reader.meta(meta::kIndexDeferred) == "1");
    CHECK(reader.count("t") == 50);  // by (topic, source, step): built now
    CHECK(reader.meta(meta::kIndexDeferred).empty());
    CHECK(visit(reader, Order::kStep).front().first == 0);
  }
  {
    // Opened again to write (a resumed run): nothing left to defer.
    Recording writer(path.string(), Recording::Access::kCreate);
    writer.insert("t", 50, "a", 0, {1});
  }
  CHECK(Recording(path.string(), Recording::Access::kRead).meta(meta::kIndexDeferred).empty());
  std::filesystem::remove(path);
  std::filesystem::remove(path.string() + "-wal");
  std::filesystem::remove(path.string() + "-shm");
}

TEST_CASE("What an observer counted is kept as the recording closes, its last rows included", "[bus][recording]") {
  const auto path = std::filesystem::temp_directory_path() /
                    ("flatsat-recording-observed-" + std::to_string(::getpid()) + ".sqlite");
  std::filesystem::remove(path);
  const auto write = [&path](int rows, int after_commit) {
    int seen = 0;
    Recording writer(path.string(), Recording::Access::kCreate);
    writer.observeStored([&seen](const flatsat::bus::StoredSample&) { ++seen; });
    writer.keepOnClose("seen", [&seen] { return std::to_string(seen); });
    for (int i = 0; i < rows; ++i) writer.insert("t", static_cast<std::uint64_t>(i), "a", 0, {1});
    writer.commit();
    // As the rig's last health comes: after the recorder's last commit.
    for (int i = 0; i < after_commit; ++i) writer.insert("h", 0, "b", 0, {2});
  };
  write(3, 2);
  CHECK(Recording(path.string(), Recording::Access::kRead).meta("seen") == "5");
  // Opened again with samples in it: what it saw is not the whole recording.
  write(1, 0);
  CHECK(Recording(path.string(), Recording::Access::kRead).meta("seen").empty());
  std::filesystem::remove(path);
  std::filesystem::remove(path.string() + "-wal");
  std::filesystem::remove(path.string() + "-shm");
}

TEST_CASE("A recording's writer thread keeps arrival order and hides nothing from reads or other readers",
          "[bus][recording]") {
  const auto path = std::filesystem::temp_directory_path() /
                    ("flatsat-recording-writer-" + std::to_string(::getpid()) + ".sqlite");
  std::filesystem::remove(path);
  {
    Recording writer(path.string(), Recording::Access::kCreate);
    // Batches handed to the writer thread while more rows queue behind them.
    std::uint64_t step = 0;
    for (int batch = 0; batch < 20; ++batch) {
      for (int i = 0; i < 97; ++i, ++step) {
        writer.insert("t", 5000 - step, step % 2 ? "odd" : "even", static_cast<std::int64_t>(step),
                      std::vector<std::uint8_t>(step % 300, static_cast<std::uint8_t>(step)));
      }
      writer.commitInBackground();
    }
    for (int i = 0; i < 13; ++i, ++step) writer.insert("t", 5000 - step, "late", 0, {1, 2, 3});
    // Read on the writing connection: the queued rows too, after the handed ones.
    const auto seen = visit(writer, Order::kArrival);
    REQUIRE(seen.size() == step);
    for (std::uint64_t i = 0; i < step; ++i) CHECK(seen[i].first == 5000 - i);
    CHECK(seen.back().second == "late");
    writer.commit();
    // Another connection sees everything once commit() returned.
    const Recording reader(path.string(), Recording::Access::kRead);
    CHECK(reader.count("t") == step);
    std::vector<std::uint8_t> payload;
    reader.forEachAt("t", 5000 - 299, [&](const std::string& source, const std::vector<std::uint8_t>& p) {
      CHECK(source == "odd");
      payload = p;
    });
    CHECK(payload == std::vector<std::uint8_t>(299, static_cast<std::uint8_t>(299)));
  }
  std::filesystem::remove(path);
  std::filesystem::remove(path.string() + "-wal");
  std::filesystem::remove(path.string() + "-shm");
}

TEST_CASE("A commit through a step leaves the later rows to the next commit, in their order", "[bus][recording]") {
  const auto path = std::filesystem::temp_directory_path() /
                    ("flatsat-recording-through-" + std::to_string(::getpid()) + ".sqlite");
  const auto removeAll = [&] {
    std::filesystem::remove(path);
    std::filesystem::remove(path.string() + "-wal");
    std::filesystem::remove(path.string() + "-shm");
  };
  const auto insertSteps = [](Recording& r, std::uint64_t first, std::uint64_t last) {
    for (std::uint64_t step = first; step <= last; ++step) {
      r.insert("t", step, "a", 0, {static_cast<std::uint8_t>(step)});
      r.insert("u", step, "b", 0, {1});
    }
  };
  removeAll();
  // A recorder trailing the rig holds samples of steps 5..7 when it commits
  // through step 4, and is then killed: its recording ends at step 4.
  const pid_t child = ::fork();
  if (child == 0) {
    Recording writer(path.string(), Recording::Access::kCreate);
    insertSteps(writer, 0, 7);
    writer.commitInBackgroundThrough(4);
    (void)writer.meta("none");  // waits for the writer; steps 5..7 go into the open transaction
    ::_exit(0);
  }
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  REQUIRE(WIFEXITED(status));
  {
    const Recording crashed(path.string(), Recording::Access::kRead);
    CHECK(crashed.count("t") == 5);
    CHECK(crashed.count("u") == 5);
    CHECK(crashed.lastStep("t") == 4u);
  }
  removeAll();
  {
    Recording writer(path.string(), Recording::Access::kCreate);
    insertSteps(writer, 0, 7);
    writer.commitInBackgroundThrough(4);
    insertSteps(writer, 8, 9);
    writer.commit();
  }
  const Recording r(path.string(), Recording::Access::kRead);
  const auto seen = visit(r, Order::kArrival);
  REQUIRE(seen.size() == 10);
  for (std::uint64_t i = 0; i < seen.size(); ++i) CHECK(seen[i].first == i);
  CHECK(r.count("u") == 10);
  removeAll();
}
