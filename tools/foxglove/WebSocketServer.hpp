// SPDX-License-Identifier: Apache-2.0
#pragma once
// A WebSocket server on websocketpp (Debian's libwebsocketpp-dev) with
// standalone Asio, behind an interface of plain types: websocketpp 0.8 does
// not compile as C++20, so only WebSocketServer.cpp sees it (built as C++17).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace flatsat::foxglove {

/// A connection, as the server names it to its handlers (never reused).
using ClientId = std::uint64_t;

struct WebSocketHandlers {
  std::function<void(ClientId)> opened;
  std::function<void(ClientId)> closed;
  std::function<void(ClientId, const std::string& text)> text;
  std::function<void(ClientId, const std::string& bytes)> binary;
};

/// Accepts connections that ask for `subprotocol` (others are refused in the
/// handshake) on its own thread; the handlers run on that thread, one at a time.
class WebSocketServer {
 public:
  /// Listens on address:port (port 0: one the system picks, see port()).
  /// @throws std::runtime_error naming the address when it cannot listen.
  WebSocketServer(const std::string& address, std::uint16_t port, std::string subprotocol, WebSocketHandlers handlers);
  ~WebSocketServer();  // closes every connection and joins the thread
  WebSocketServer(const WebSocketServer&) = delete;
  WebSocketServer& operator=(const WebSocketServer&) = delete;

  std::uint16_t port() const;
  /// Queue a message to one client from any thread. A client whose unsent
  /// backlog exceeds `backlog_limit_bytes` misses it (a slow viewer must not
  /// grow the bridge without bound; counted in backlogDrops()). False when
  /// the client has gone.
  bool sendText(ClientId client, std::string text);
  bool sendBinary(ClientId client, std::string bytes);
  /// Between the two, queued messages wait for endBatch(), which hands them to
  /// the server's thread at once: a burst known to be whole (a step's batch
  /// from the recorder's feed) needs no gathering delay. From one thread.
  void beginBatch();
  void endBatch();
  /// Messages missed for a full backlog, over all clients.
  std::uint64_t backlogDrops() const;

  static constexpr std::size_t backlog_limit_bytes = 16u << 20;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace flatsat::foxglove
