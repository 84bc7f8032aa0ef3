// SPDX-License-Identifier: Apache-2.0
#define ASIO_STANDALONE
#define _WEBSOCKETPP_CPP11_STL_
#include "tools/foxglove/WebSocketServer.hpp"

#include <atomic>
#include <map>
#include <optional>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

namespace flatsat::foxglove {

using Server = websocketpp::server<websocketpp::config::asio>;
using Handle = websocketpp::connection_hdl;

struct WebSocketServer::Impl {
  Server server;
  WebSocketHandlers handlers;
  std::string subprotocol;
  std::mutex mutex;  // guards clients (the senders are other threads)
  std::map<ClientId, Handle> clients;
  std::map<Handle, ClientId, std::owner_less<Handle>> ids;
  ClientId next_id = 1;
  std::atomic<std::uint64_t> drops{0};
  std::uint16_t port = 0;
  std::thread thread;

  std::optional<ClientId> idOf(const Handle& h) {
    std::lock_guard lock(mutex);
    const auto it = ids.find(h);
    if (it == ids.end()) return std::nullopt;
    return it->second;
  }

  // Messages wait here for the server's thread, which takes them all at once:
  // a burst of samples (a step's worth) costs it one wake-up, not one each.
  struct Outgoing {
    ClientId client;
    std::string payload;
    websocketpp::frame::opcode::value opcode;
  };
  std::mutex queue_mutex;
  std::vector<Outgoing> queue;
  bool flush_posted = false;
  int batches = 0;  // open batches: what is queued waits for the last to end
  std::unique_ptr<asio::steady_timer> flush_timer;

  bool send(ClientId client, std::string payload, websocketpp::frame::opcode::value opcode) {
    {
      std::lock_guard lock(mutex);
      if (clients.count(client) == 0) return false;
    }
    std::lock_guard lock(queue_mutex);
    queue.push_back({client, std::move(payload), opcode});
    if (!flush_posted && batches == 0) {
      flush_posted = true;
      asio::post(server.get_io_service(), [this] { scheduleFlush(); });
    }
    return true;
  }

  void endBatch() {
    std::lock_guard lock(queue_mutex);
    if (--batches > 0 || flush_posted || queue.empty()) return;
    flush_posted = true;
    asio::post(server.get_io_service(), [this] { flush(); });
  }

  /// On the server's thread: the queue is sent a few milliseconds after its
  /// first message, so that the rest of the burst joins it.
  void scheduleFlush() {
    flush_timer->expires_after(std::chrono::milliseconds(5));
    flush_timer->async_wait([this](const std::error_code& ec) {
      if (!ec) flush();
    });
  }

  void flush() {
    std::vector<Outgoing> taken;
    {
      std::lock_guard lock(queue_mutex);
      taken.swap(queue);
      flush_posted = false;
    }
    for (auto& message : taken) {
      Handle h;
      {
        std::lock_guard lock(mutex);
        const auto it = clients.find(message.client);
        if (it == clients.end()) continue;
        h = it->second;
      }
      std::error_code ec;
      const auto connection = server.get_con_from_hdl(h, ec);
      if (ec) continue;
      if (connection->get_buffered_amount() > backlog_limit_bytes) {
        drops.fetch_add(1, std::memory_order_relaxed);
        continue;
      }
      connection->send(message.payload, message.opcode);  // fails only on a closing connection: nothing to do
    }
  }
};

WebSocketServer::WebSocketServer(const std::string& address, std::uint16_t port, std::string subprotocol,
                                 WebSocketHandlers handlers)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.handlers = std::move(handlers);
  s.subprotocol = std::move(subprotocol);
  s.server.clear_access_channels(websocketpp::log::alevel::all);
  s.server.clear_error_channels(websocketpp::log::elevel::all);
  s.server.init_asio();
  s.flush_timer = std::make_unique<asio::steady_timer>(s.server.get_io_service());
  s.server.set_reuse_addr(true);
  // RFC 6455, 4.2.2: the server selects one of the client's subprotocols or refuses.
  s.server.set_validate_handler([&s](Handle h) {
    const auto connection = s.server.get_con_from_hdl(h);
    for (const auto& offered : connection->get_requested_subprotocols()) {
      if (offered == s.subprotocol) {
        connection->select_subprotocol(offered);
        return true;
      }
    }
    connection->set_status(websocketpp::http::status_code::bad_request);
    connection->set_body("this server speaks the WebSocket subprotocol " + s.subprotocol + " only\n");
    return false;
  });
  s.server.set_open_handler([&s](Handle h) {
    ClientId id = 0;
    {
      std::lock_guard lock(s.mutex);
      id = s.next_id++;
      s.clients[id] = h;
      s.ids[h] = id;
    }
    if (s.handlers.opened) s.handlers.opened(id);
  });
  s.server.set_close_handler([&s](Handle h) {
    ClientId id = 0;
    {
      std::lock_guard lock(s.mutex);
      const auto it = s.ids.find(h);
      if (it == s.ids.end()) return;
      id = it->second;
      s.clients.erase(id);
      s.ids.erase(it);
    }
    if (s.handlers.closed) s.handlers.closed(id);
  });
  s.server.set_message_handler([&s](Handle h, Server::message_ptr message) {
    const auto id = s.idOf(h);
    if (!id) return;
    if (message->get_opcode() == websocketpp::frame::opcode::text) {
      if (s.handlers.text) s.handlers.text(*id, message->get_payload());
    } else if (s.handlers.binary) {
      s.handlers.binary(*id, message->get_payload());
    }
  });
  std::error_code ec;
  asio::ip::tcp::endpoint endpoint(asio::ip::make_address(address, ec), port);
  if (ec) throw std::runtime_error("'" + address + "' is not an IP address: " + ec.message());
  s.server.listen(endpoint, ec);
  if (ec) throw std::runtime_error("cannot listen on " + address + ":" + std::to_string(port) + ": " + ec.message());
  s.server.start_accept(ec);
  if (ec) throw std::runtime_error("cannot accept on " + address + ":" + std::to_string(port) + ": " + ec.message());
  asio::error_code local_ec;
  s.port = s.server.get_local_endpoint(local_ec).port();
  s.thread = std::thread([&s] { s.server.run(); });
}

WebSocketServer::~WebSocketServer() {
  Impl& s = *impl_;
  asio::post(s.server.get_io_service(), [&s] {
    std::error_code ec;
    s.server.stop_listening(ec);
    std::map<ClientId, Handle> open;
    {
      std::lock_guard lock(s.mutex);
      open = s.clients;
    }
    for (const auto& [id, h] : open) s.server.close(h, websocketpp::close::status::going_away, "bridge stopping", ec);
  });
  // Closing handshakes get a moment; then the loop is stopped whatever is left.
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  s.server.stop();
  if (s.thread.joinable()) s.thread.join();
}

std::uint16_t WebSocketServer::port() const { return impl_->port; }
bool WebSocketServer::sendText(ClientId client, std::string text) {
  return impl_->send(client, std::move(text), websocketpp::frame::opcode::text);
}
bool WebSocketServer::sendBinary(ClientId client, std::string bytes) {
  return impl_->send(client, std::move(bytes), websocketpp::frame::opcode::binary);
}
void WebSocketServer::beginBatch() {
  std::lock_guard lock(impl_->queue_mutex);
  ++impl_->batches;
}
void WebSocketServer::endBatch() { impl_->endBatch(); }
std::uint64_t WebSocketServer::backlogDrops() const { return impl_->drops.load(std::memory_order_relaxed); }

}  // namespace flatsat::foxglove
