// SPDX-License-Identifier: Apache-2.0
#pragma once
// The Foxglove WebSocket protocol, subprotocol foxglove.websocket.v1
// (github.com/foxglove/ws-protocol, docs/spec.md): the server's messages as
// text or binary frames, the client's parsed, and who subscribed to what.
// No sockets here: WebSocketServer carries the frames.
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace flatsat::foxglove {

inline constexpr const char* kSubprotocol = "foxglove.websocket.v1";

/// A channel the server advertises (spec: "Advertise").
struct Channel {
  std::uint32_t id = 0;
  std::string topic;
  std::string encoding;        ///< "cdr"
  std::string schema_name;     ///< the IDL type, e.g. flatsat::msg::GyroSample
  std::string schema;          ///< its IDL text
  std::string schema_encoding; ///< "omgidl"
};

enum class StatusLevel { kInfo = 0, kWarning = 1, kError = 2 };

std::string serverInfo(const std::string& name, const std::vector<std::string>& capabilities,
                       const std::vector<std::string>& supported_encodings,
                       const std::map<std::string, std::string>& metadata, const std::string& session_id);
std::string advertise(const std::vector<Channel>& channels);
std::string status(StatusLevel level, const std::string& message, const std::string& id = "");
/// Binary "Message Data": opcode 0x01, subscription id (u32 LE), timestamp
/// [ns] (u64 LE), the message's bytes.
std::string messageData(std::uint32_t subscription_id, std::uint64_t timestamp_ns, const std::uint8_t* data,
                        std::size_t size);

// What a client may send.
struct Subscribe {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> subscriptions;  ///< (subscription id, channel id)
};
struct Unsubscribe {
  std::vector<std::uint32_t> subscription_ids;
};
struct ClientChannel {
  std::uint32_t id = 0;
  std::string topic, encoding, schema_name;
};
struct ClientAdvertise {
  std::vector<ClientChannel> channels;
};
struct ClientUnadvertise {
  std::vector<std::uint32_t> channel_ids;
};
struct ClientMessageData {
  std::uint32_t channel_id = 0;
  std::vector<std::uint8_t> data;
};
using ClientRequest = std::variant<Subscribe, Unsubscribe, ClientAdvertise, ClientUnadvertise, ClientMessageData>;

/// A client message that is not the protocol, or not what this server offers;
/// what() says which field and why (sent back as an error status).
struct ProtocolError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// @throws ProtocolError for bad JSON, an unknown or unsupported op, a
/// missing field or one of the wrong type.
ClientRequest parseText(const std::string& text);
/// @throws ProtocolError for an unknown opcode or a frame too short.
ClientRequest parseBinary(const std::string& bytes);

/// Which client's subscription ids stand for which channel.
template <class Client>
class Subscriptions {
 public:
  /// @throws ProtocolError when the id is taken by this client already.
  void add(Client client, std::uint32_t subscription_id, std::uint32_t channel_id) {
    auto& mine = by_client_[client];
    if (mine.count(subscription_id) != 0) {
      throw ProtocolError("subscription id " + std::to_string(subscription_id) + " is already in use");
    }
    mine[subscription_id] = channel_id;
  }
  /// @throws ProtocolError when this client has no such subscription.
  void remove(Client client, std::uint32_t subscription_id) {
    auto& mine = by_client_[client];
    if (mine.erase(subscription_id) == 0) {
      throw ProtocolError("no subscription " + std::to_string(subscription_id) + " to remove");
    }
  }
  void forget(Client client) { by_client_.erase(client); }
  /// Every (client, subscription id) that subscribed to `channel_id`.
  std::vector<std::pair<Client, std::uint32_t>> of(std::uint32_t channel_id) const {
    std::vector<std::pair<Client, std::uint32_t>> out;
    for (const auto& [client, mine] : by_client_) {
      for (const auto& [subscription, channel] : mine) {
        if (channel == channel_id) out.emplace_back(client, subscription);
      }
    }
    return out;
  }

 private:
  std::map<Client, std::map<std::uint32_t, std::uint32_t>> by_client_;
};

/// A component's condition, as its health and its writer's liveliness tell it.
struct ComponentCondition {
  std::string state;    ///< ComponentState's name: STARTING, READY, RUNNING, STOPPED, FAILED
  bool alive = true;    ///< false: its health writer's liveliness lapsed, or its participant left
  std::string message;  ///< the health's last notable event
};

/// The status a change of a component's condition is reported with; nothing
/// when nothing an operator acts on changed. A component that failed, or went
/// away without stopping, is an error; one that stopped (a run that
/// completed) is information, also once its process has gone.
std::optional<std::pair<StatusLevel, std::string>> conditionChange(const std::string& component,
                                                                   const std::optional<ComponentCondition>& before,
                                                                   const ComponentCondition& now);

}  // namespace flatsat::foxglove
