// SPDX-License-Identifier: Apache-2.0
#pragma once
// The recorder's live feed: every sample it takes, as it takes it, to local
// watchers (`flatsat foxglove`) over a Unix socket of the host.
//
// Why: the recorder already receives every topic of the rig. A watcher that
// subscribed to every topic itself would pay Fast DDS's receive path (a
// thread wake-up per sample and reader) a second time, and its participant's
// discovery and liveliness traffic besides: measured on the paced default
// rig, about 14 % of the rig's CPU for a bridge with one client watching
// everything. Through the feed the recorder sends one batch per step, and the
// watcher needs no participant (docs/recordings.md, "What the bridge costs").
//
// The socket is abstract (Linux): no file to leave behind, and seen only in
// the recorder's network namespace, so a watcher in another container falls
// back to reading the bus itself.
//
// Frames, little endian: u32 length of the rest, u8 kind, u16 name length,
// the name, then by kind: kSample i64 simulated time [ns] and the sample's
// CDR bytes (with their encapsulation header); kLiveliness u8 alive;
// kHello, kEnd nothing. The stream opens with kHello named kLiveFeedVersion.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

namespace flatsat::bus {

inline constexpr std::string_view kLiveFeedVersion = "flatsat-live-1";

enum class LiveFrameKind : std::uint8_t {
  kHello = 0,
  kSample = 1,      ///< name: the topic
  kLiveliness = 2,  ///< name: the component whose health writer's liveliness changed
  kEnd = 3,         ///< the recorder stopped in order: the run is over
};

/// One frame, its name and bytes viewed in the reader's buffer (valid during the callback).
struct LiveFrame {
  LiveFrameKind kind = LiveFrameKind::kHello;
  std::string_view name;
  std::int64_t sim_time_ns = 0;
  bool alive = false;
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};

class LiveFeedError : public std::runtime_error {
  using std::runtime_error::runtime_error;
};

void appendLiveSample(std::string& out, std::string_view topic, std::int64_t sim_time_ns, const std::uint8_t* data,
                      std::size_t size);
void appendLiveFrame(std::string& out, LiveFrameKind kind, std::string_view name, bool alive = false);

/// Cuts a byte stream into frames; throws LiveFeedError on a frame that is not one.
class LiveFrameReader {
 public:
  void append(const char* bytes, std::size_t size) { buffer_.append(bytes, size); }
  /// Calls on_frames once with every whole frame buffered (none: not called);
  /// keeps a partial one.
  void drain(const std::function<void(const std::vector<LiveFrame>&)>& on_frames);

 private:
  std::string buffer_;
};

/// The abstract socket name of `domain`'s feed.
std::string liveFeedName(std::uint32_t domain);

/// The recorder's end: frames gather until flush(), which sends them to every
/// watcher without blocking. A watcher that does not keep up loses whole
/// frames (counted), never the recorder's time.
class LiveFeedServer {
 public:
  /// Throws LiveFeedError when the name is taken (another recorder of the same
  /// domain on this host) or sockets fail.
  explicit LiveFeedServer(const std::string& name);
  ~LiveFeedServer();
  LiveFeedServer(const LiveFeedServer&) = delete;
  LiveFeedServer& operator=(const LiveFeedServer&) = delete;

  /// Whether anyone watches: unwatched, the recorder skips the feed entirely.
  bool watched() const { return watchers_.load(std::memory_order_relaxed) > 0; }
  void sample(std::string_view topic, std::int64_t sim_time_ns, const std::uint8_t* data, std::size_t size);
  void liveliness(std::string_view component, bool alive);
  /// kEnd, sent at once.
  void end();
  void flush();
  /// flush() unless one ran within `quiet`: a rare frame rides with the next
  /// step's batch, and goes alone only when no step comes (a stalled rig).
  void flushUnlessRecent(std::chrono::steady_clock::duration quiet);
  std::uint64_t framesDropped() const { return dropped_.load(std::memory_order_relaxed); }

  /// [bytes] What a watcher may have unsent before frames for it are dropped.
  static constexpr std::size_t kBacklogLimit = 8u << 20;
  /// Watchers at once; more are closed as they come (each may cost kBacklogLimit).
  static constexpr std::size_t kMaxWatchers = 8;

 private:
  struct Watcher {
    int fd = -1;
    std::string unsent;
  };
  void accept();
  void sendTo(Watcher& w, const std::string& frames, std::size_t frame_count);

  int listen_fd_ = -1;
  int wake_fd_ = -1;  // eventfd: stops the accepting thread
  std::mutex mutex_;
  std::string pending_;
  std::size_t pending_frames_ = 0;
  std::vector<Watcher> watchers_list_;
  std::atomic<int> watchers_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::chrono::steady_clock::time_point last_flush_{};
  std::thread acceptor_;
};

/// A watcher's end: a thread reads the feed and hands every frame to
/// `on_frame`; `on_closed` runs once when the feed ends or breaks.
class LiveFeedClient {
 public:
  using OnFrames = std::function<void(const std::vector<LiveFrame>&)>;
  using OnClosed = std::function<void(bool ended_in_order, const std::string& why)>;
  /// nullptr when nobody listens on `name`. Throws LiveFeedError when the
  /// listener runs as another user (not root). A feed of another version is
  /// closed at once (on_closed says so).
  static std::unique_ptr<LiveFeedClient> connect(const std::string& name, OnFrames on_frames, OnClosed on_closed);
  ~LiveFeedClient();
  LiveFeedClient(const LiveFeedClient&) = delete;
  LiveFeedClient& operator=(const LiveFeedClient&) = delete;

 private:
  LiveFeedClient(int fd, OnFrames on_frames, OnClosed on_closed);
  void run();

  int fd_;
  OnFrames on_frames_;
  OnClosed on_closed_;
  LiveFrameReader reader_;
  std::atomic<bool> closing_{false};
  std::thread thread_;
};

}  // namespace flatsat::bus
