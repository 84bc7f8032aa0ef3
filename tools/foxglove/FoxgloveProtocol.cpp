// SPDX-License-Identifier: Apache-2.0
#include "tools/foxglove/FoxgloveProtocol.hpp"

#include <cstring>

#include <nlohmann/json.hpp>

namespace flatsat::foxglove {

using Json = nlohmann::json;

namespace {

void appendLe(std::string& out, std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xFF));
}

std::uint64_t readLe(const std::string& in, std::size_t at, int bytes) {
  std::uint64_t value = 0;
  for (int i = bytes - 1; i >= 0; --i) value = (value << 8) | static_cast<unsigned char>(in[at + static_cast<std::size_t>(i)]);
  return value;
}

/// The field `key` of `object`, as T; ProtocolError naming `where` and the key otherwise.
template <class T>
T field(const Json& object, const char* key, const std::string& where) {
  if (!object.is_object() || !object.contains(key)) throw ProtocolError(where + ": no field '" + key + "'");
  const Json& value = object.at(key);
  if constexpr (std::is_same_v<T, std::string>) {
    if (!value.is_string()) throw ProtocolError(where + ": '" + key + "' must be a string");
  } else if constexpr (std::is_same_v<T, std::uint32_t>) {
    if (!value.is_number_unsigned() || value.get<std::uint64_t>() > 0xFFFFFFFFull) {
      throw ProtocolError(where + ": '" + key + "' must be an integer 0..4294967295");
    }
  } else {
    if (!value.is_array()) throw ProtocolError(where + ": '" + key + "' must be an array");
  }
  return value.get<T>();
}

/// The array `key` of ids, each an integer 0..4294967295.
std::vector<std::uint32_t> ids(const Json& object, const char* key, const std::string& where) {
  std::vector<std::uint32_t> out;
  for (const auto& id : field<Json::array_t>(object, key, where)) {
    if (!id.is_number_unsigned() || id.get<std::uint64_t>() > 0xFFFFFFFFull) {
      throw ProtocolError(where + ": '" + key + "' must hold integers 0..4294967295");
    }
    out.push_back(id.get<std::uint32_t>());
  }
  return out;
}

}  // namespace

std::string serverInfo(const std::string& name, const std::vector<std::string>& capabilities,
                       const std::vector<std::string>& supported_encodings,
                       const std::map<std::string, std::string>& metadata, const std::string& session_id) {
  return Json{{"op", "serverInfo"},
              {"name", name},
              {"capabilities", capabilities},
              {"supportedEncodings", supported_encodings},
              {"metadata", metadata},
              {"sessionId", session_id}}
      .dump();
}

std::string advertise(const std::vector<Channel>& channels) {
  auto list = Json::array();
  for (const auto& c : channels) {
    list.push_back({{"id", c.id},
                    {"topic", c.topic},
                    {"encoding", c.encoding},
                    {"schemaName", c.schema_name},
                    {"schema", c.schema},
                    {"schemaEncoding", c.schema_encoding}});
  }
  return Json{{"op", "advertise"}, {"channels", list}}.dump();
}

std::string status(StatusLevel level, const std::string& message, const std::string& id) {
  Json j{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}};
  if (!id.empty()) j["id"] = id;
  // Health messages come from the bus: anything not UTF-8 is replaced, never thrown on.
  return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

std::string messageData(std::uint32_t subscription_id, std::uint64_t timestamp_ns, const std::uint8_t* data,
                        std::size_t size) {
  std::string frame;
  frame.reserve(1 + 4 + 8 + size);
  frame.push_back(0x01);
  appendLe(frame, subscription_id, 4);
  appendLe(frame, timestamp_ns, 8);
  frame.append(reinterpret_cast<const char*>(data), size);
  return frame;
}

ClientRequest parseText(const std::string& text) {
  Json j;
  try {
    j = Json::parse(text);
  } catch (const Json::parse_error& e) {
    throw ProtocolError(std::string("not JSON: ") + e.what());
  }
  if (!j.is_object()) throw ProtocolError("a client message must be a JSON object");
  const auto op = field<std::string>(j, "op", "client message");
  const std::string where = "op '" + op + "'";
  if (op == "subscribe") {
    Subscribe s;
    for (const auto& item : field<Json::array_t>(j, "subscriptions", where)) {
      s.subscriptions.emplace_back(field<std::uint32_t>(item, "id", where + " subscription"),
                                   field<std::uint32_t>(item, "channelId", where + " subscription"));
    }
    return s;
  }
  if (op == "unsubscribe") {
    return Unsubscribe{ids(j, "subscriptionIds", where)};
  }
  if (op == "advertise") {
    ClientAdvertise a;
    for (const auto& item : field<Json::array_t>(j, "channels", where)) {
      a.channels.push_back({field<std::uint32_t>(item, "id", where + " channel"),
                            field<std::string>(item, "topic", where + " channel"),
                            field<std::string>(item, "encoding", where + " channel"),
                            field<std::string>(item, "schemaName", where + " channel")});
    }
    return a;
  }
  if (op == "unadvertise") {
    return ClientUnadvertise{ids(j, "channelIds", where)};
  }
  throw ProtocolError("op '" + op + "' is not supported by this server (it offers subscribe, unsubscribe, and "
                      "advertise, unadvertise and message data for the operator command topics)");
}

ClientRequest parseBinary(const std::string& bytes) {
  if (bytes.empty()) throw ProtocolError("an empty binary message");
  const auto opcode = static_cast<unsigned char>(bytes[0]);
  if (opcode != 0x01) {
    throw ProtocolError("binary opcode " + std::to_string(opcode) + " is not supported (only 1, client message data)");
  }
  if (bytes.size() < 5) throw ProtocolError("client message data shorter than its 5-byte head");
  ClientMessageData m;
  m.channel_id = static_cast<std::uint32_t>(readLe(bytes, 1, 4));
  m.data.assign(bytes.begin() + 5, bytes.end());
  return m;
}

std::optional<std::pair<StatusLevel, std::string>> conditionChange(const std::string& component,
                                                                   const std::optional<ComponentCondition>& before,
                                                                   const ComponentCondition& now) {
  if (before && before->state == now.state && before->alive == now.alive && before->message == now.message) {
    return std::nullopt;
  }
  const std::string said = now.message.empty() ? "" : ": " + now.message;
  if (now.state == "FAILED") return std::make_pair(StatusLevel::kError, component + " FAILED" + said);
  if (!now.alive) {
    if (now.state == "STOPPED") return std::make_pair(StatusLevel::kInfo, component + " stopped and has gone");
    return std::make_pair(StatusLevel::kError,
                          component + " lost while " + now.state + " (its health lapsed; it did not stop)");
  }
  return std::make_pair(StatusLevel::kInfo, component + " " + now.state + said);
}

}  // namespace flatsat::foxglove
