// SPDX-License-Identifier: Apache-2.0
#include "bus/LiveFeed.hpp"

#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace flatsat::bus {

namespace {

constexpr std::size_t kLengthBytes = 4;
constexpr std::size_t kHeadBytes = 1 + 2;  // kind, name length
/// [bytes] Larger than any registry sample; a longer frame is a broken stream.
constexpr std::uint32_t kMaxFrameBytes = 16u << 20;

template <class T>
void appendLe(std::string& out, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i) out.push_back(static_cast<char>((static_cast<std::uint64_t>(value) >> (8 * i)) & 0xff));
}
template <class T>
T readLe(const char* p) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) v |= std::uint64_t{static_cast<unsigned char>(p[i])} << (8 * i);
  return static_cast<T>(v);
}

void appendHead(std::string& out, std::size_t rest, LiveFrameKind kind, std::string_view name) {
  if (name.size() > 0xffff) throw LiveFeedError("live feed: a name of " + std::to_string(name.size()) + " bytes");
  appendLe(out, static_cast<std::uint32_t>(kHeadBytes + name.size() + rest));
  out.push_back(static_cast<char>(kind));
  appendLe(out, static_cast<std::uint16_t>(name.size()));
  out.append(name);
}

sockaddr_un abstractAddress(const std::string& name, socklen_t& length) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (name.size() + 1 > sizeof(address.sun_path)) throw LiveFeedError("live feed name too long: " + name);
  std::memcpy(address.sun_path + 1, name.data(), name.size());  // sun_path[0] = 0: the abstract namespace
  length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + 1 + name.size());
  return address;
}

std::string errnoText(const std::string& what) { return what + ": " + std::strerror(errno); }

}  // namespace

void appendLiveSample(std::string& out, std::string_view topic, std::int64_t sim_time_ns, const std::uint8_t* data,
                      std::size_t size) {
  appendHead(out, 8 + size, LiveFrameKind::kSample, topic);
  appendLe(out, sim_time_ns);
  out.append(reinterpret_cast<const char*>(data), size);
}

void appendLiveFrame(std::string& out, LiveFrameKind kind, std::string_view name, bool alive) {
  const bool has_flag = kind == LiveFrameKind::kLiveliness;
  appendHead(out, has_flag ? 1 : 0, kind, name);
  if (has_flag) out.push_back(alive ? 1 : 0);
}

void LiveFrameReader::drain(const std::function<void(const std::vector<LiveFrame>&)>& on_frames) {
  std::vector<LiveFrame> frames;
  std::size_t at = 0;
  while (buffer_.size() - at >= kLengthBytes) {
    const auto length = readLe<std::uint32_t>(buffer_.data() + at);
    if (length < kHeadBytes || length > kMaxFrameBytes) {
      throw LiveFeedError("live feed: a frame of " + std::to_string(length) + " bytes");
    }
    if (buffer_.size() - at - kLengthBytes < length) break;  // the rest is still on its way
    const char* p = buffer_.data() + at + kLengthBytes;
    LiveFrame frame;
    const auto kind = static_cast<std::uint8_t>(p[0]);
    if (kind > static_cast<std::uint8_t>(LiveFrameKind::kEnd)) throw LiveFeedError("live feed: frame kind " + std::to_string(kind));
    frame.kind = static_cast<LiveFrameKind>(kind);
    const auto name_size = readLe<std::uint16_t>(p + 1);
    std::size_t rest = length - kHeadBytes;
    if (name_size > rest) throw LiveFeedError("live feed: a name longer than its frame");
    frame.name = std::string_view(p + kHeadBytes, name_size);
    rest -= name_size;
    const char* body = p + kHeadBytes + name_size;
    if (frame.kind == LiveFrameKind::kSample) {
      if (rest < 8) throw LiveFeedError("live feed: a sample frame without its time");
      frame.sim_time_ns = readLe<std::int64_t>(body);
      frame.data = reinterpret_cast<const std::uint8_t*>(body + 8);
      frame.size = rest - 8;
    } else if (frame.kind == LiveFrameKind::kLiveliness) {
      if (rest != 1) throw LiveFeedError("live feed: a liveliness frame of " + std::to_string(rest) + " bytes");
      frame.alive = body[0] != 0;
    } else if (rest != 0) {
      throw LiveFeedError("live feed: " + std::to_string(rest) + " stray bytes in a frame");
    }
    frames.push_back(frame);
    at += kLengthBytes + length;
  }
  if (!frames.empty()) on_frames(frames);  // the views stay valid until the erase
  buffer_.erase(0, at);
}

std::string liveFeedName(std::uint32_t domain) { return "flatsat-live-domain-" + std::to_string(domain); }

LiveFeedServer::LiveFeedServer(const std::string& name) {
  listen_fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0) throw LiveFeedError(errnoText("live feed socket"));
  socklen_t length = 0;
  const auto address = abstractAddress(name, length);
  if (::bind(listen_fd_, reinterpret_cast<const sockaddr*>(&address), length) != 0 || ::listen(listen_fd_, 4) != 0) {
    const auto why = errnoText("live feed '" + name + "'");
    ::close(listen_fd_);
    throw LiveFeedError(why);
  }
  wake_fd_ = ::eventfd(0, EFD_CLOEXEC);
  if (wake_fd_ < 0) {
    ::close(listen_fd_);
    throw LiveFeedError(errnoText("live feed eventfd"));
  }
  acceptor_ = std::thread([this] { accept(); });
}

LiveFeedServer::~LiveFeedServer() {
  const std::uint64_t one = 1;
  [[maybe_unused]] const auto written = ::write(wake_fd_, &one, sizeof one);
  acceptor_.join();
  for (auto& w : watchers_list_) ::close(w.fd);
  ::close(listen_fd_);
  ::close(wake_fd_);
}

void LiveFeedServer::accept() {
  pollfd fds[2] = {{listen_fd_, POLLIN, 0}, {wake_fd_, POLLIN, 0}};
  while (true) {
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      return;
    }
    if (fds[1].revents != 0) return;
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) continue;
    Watcher w{fd, {}};
    appendLiveFrame(w.unsent, LiveFrameKind::kHello, kLiveFeedVersion);
    std::lock_guard lock(mutex_);
    if (watchers_list_.size() >= kMaxWatchers) {
      ::close(fd);
      continue;
    }
    sendTo(w, {}, 0);
    if (w.fd >= 0) {
      watchers_list_.push_back(std::move(w));
      watchers_.fetch_add(1, std::memory_order_relaxed);
    }
  }
}

void LiveFeedServer::sample(std::string_view topic, std::int64_t sim_time_ns, const std::uint8_t* data,
                            std::size_t size) {
  std::lock_guard lock(mutex_);
  appendLiveSample(pending_, topic, sim_time_ns, data, size);
  ++pending_frames_;
}

void LiveFeedServer::liveliness(std::string_view component, bool alive) {
  std::lock_guard lock(mutex_);
  appendLiveFrame(pending_, LiveFrameKind::kLiveliness, component, alive);
  ++pending_frames_;
}

void LiveFeedServer::end() {
  {
    std::lock_guard lock(mutex_);
    appendLiveFrame(pending_, LiveFrameKind::kEnd, {});
    ++pending_frames_;
  }
  flush();
}

void LiveFeedServer::flushUnlessRecent(std::chrono::steady_clock::duration quiet) {
  {
    std::lock_guard lock(mutex_);
    if (std::chrono::steady_clock::now() - last_flush_ < quiet) return;
  }
  flush();
}

void LiveFeedServer::flush() {
  std::lock_guard lock(mutex_);
  last_flush_ = std::chrono::steady_clock::now();
  if (pending_.empty() && watchers_list_.empty()) return;
  for (auto& w : watchers_list_) sendTo(w, pending_, pending_frames_);
  std::erase_if(watchers_list_, [](const Watcher& w) { return w.fd < 0; });
  watchers_.store(static_cast<int>(watchers_list_.size()), std::memory_order_relaxed);
  pending_.clear();
  pending_frames_ = 0;
}

void LiveFeedServer::sendTo(Watcher& w, const std::string& frames, std::size_t frame_count) {
  if (w.unsent.size() + frames.size() > kBacklogLimit) {
    dropped_.fetch_add(frame_count, std::memory_order_relaxed);  // whole frames: the stream stays readable
  } else {
    w.unsent += frames;
  }
  while (!w.unsent.empty()) {
    const auto sent = ::send(w.fd, w.unsent.data(), w.unsent.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
    if (sent < 0) {
      if (errno == EINTR) continue;
      if (errno == EAGAIN || errno == EWOULDBLOCK) return;  // the rest goes at the next flush
      ::close(w.fd);  // the watcher went away
      w.fd = -1;
      return;
    }
    w.unsent.erase(0, static_cast<std::size_t>(sent));
  }
}

std::unique_ptr<LiveFeedClient> LiveFeedClient::connect(const std::string& name, OnFrames on_frames, OnClosed on_closed) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw LiveFeedError(errnoText("live feed socket"));
  socklen_t length = 0;
  const auto address = abstractAddress(name, length);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), length) != 0) {
    ::close(fd);
    return nullptr;
  }
  // Anyone on the host may take an abstract name first: only a feed of this
  // user (or root's) is believed.
  ucred peer{};
  socklen_t peer_size = sizeof peer;
  if (::getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &peer, &peer_size) != 0 || (peer.uid != ::getuid() && peer.uid != 0)) {
    ::close(fd);
    throw LiveFeedError("the live feed '" + name + "' belongs to user " + std::to_string(peer.uid) + ", not to this one");
  }
  return std::unique_ptr<LiveFeedClient>(new LiveFeedClient(fd, std::move(on_frames), std::move(on_closed)));
}

LiveFeedClient::LiveFeedClient(int fd, OnFrames on_frames, OnClosed on_closed)
    : fd_(fd), on_frames_(std::move(on_frames)), on_closed_(std::move(on_closed)) {
  thread_ = std::thread([this] { run(); });
}

LiveFeedClient::~LiveFeedClient() {
  closing_ = true;
  ::shutdown(fd_, SHUT_RDWR);  // wakes the reading thread
  thread_.join();
  ::close(fd_);
}

void LiveFeedClient::run() {
  bool greeted = false;
  bool ended = false;
  std::string why = "the recorder's feed broke off without its end (the recorder stopped unexpectedly)";
  std::vector<char> chunk(1 << 16);
  try {
    while (!ended) {
      const auto got = ::recv(fd_, chunk.data(), chunk.size(), 0);
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) break;
      reader_.append(chunk.data(), static_cast<std::size_t>(got));
      reader_.drain([&](const std::vector<LiveFrame>& frames) {
        std::vector<LiveFrame> news;
        for (const auto& frame : frames) {
          if (ended) break;
          if (!greeted) {
            if (frame.kind != LiveFrameKind::kHello || frame.name != kLiveFeedVersion) {
              throw LiveFeedError("the feed speaks '" + std::string(frame.name) + "', not " +
                                  std::string(kLiveFeedVersion));
            }
            greeted = true;
          } else if (frame.kind == LiveFrameKind::kEnd) {
            ended = true;
            why = "the recorder stopped and ended its feed";
          } else {
            news.push_back(frame);
          }
        }
        if (!news.empty()) on_frames_(news);
      });
    }
  } catch (const LiveFeedError& e) {
    why = e.what();
  } catch (const std::exception& e) {
    why = std::string("the feed's frames could not be taken: ") + e.what();
  }
  if (!closing_) on_closed_(ended, why);
}

}  // namespace flatsat::bus
