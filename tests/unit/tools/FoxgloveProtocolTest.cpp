// SPDX-License-Identifier: Apache-2.0
// The Foxglove WebSocket protocol's messages against its specification
// (github.com/foxglove/ws-protocol, docs/spec.md): field names, the binary
// Message Data layout, what a client may send and how each error is named.
// tests/interop/foxglove-check.mjs talks to the bridge with the published client.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "tools/foxglove/FoxgloveProtocol.hpp"

using namespace flatsat::foxglove;
using Json = nlohmann::json;

TEST_CASE("the server's Foxglove messages carry the specification's field names", "[foxglove]") {
  const auto info = Json::parse(serverInfo("flatsat", {"clientPublish"}, {"cdr"}, {{"domain", "12"}}, "s1"));
  CHECK(info["op"] == "serverInfo");
  CHECK(info["capabilities"] == Json::array({"clientPublish"}));
  CHECK(info["supportedEncodings"] == Json::array({"cdr"}));
  CHECK(info["metadata"]["domain"] == "12");
  CHECK(info["sessionId"] == "s1");
  const auto ad = Json::parse(advertise({{3, "flatsat/gyro", "cdr", "flatsat::msg::GyroReading", "struct X {};", "omgidl"}}));
  CHECK(ad["op"] == "advertise");
  REQUIRE(ad["channels"].size() == 1);
  CHECK(ad["channels"][0] == Json{{"id", 3}, {"topic", "flatsat/gyro"}, {"encoding", "cdr"},
                                  {"schemaName", "flatsat::msg::GyroReading"}, {"schema", "struct X {};"},
                                  {"schemaEncoding", "omgidl"}});
  const auto st = Json::parse(status(StatusLevel::kError, "gyro lost", "h1"));
  CHECK(st == Json{{"op", "status"}, {"level", 2}, {"message", "gyro lost"}, {"id", "h1"}});
  CHECK_FALSE(Json::parse(status(StatusLevel::kInfo, "x")).contains("id"));
  // Text from the bus that is not UTF-8 is replaced, not thrown on.
  CHECK_NOTHROW(Json::parse(status(StatusLevel::kInfo, std::string("bad \xff byte"))));
}

TEST_CASE("Message Data is opcode 1, the subscription id and the timestamp little-endian, then the bytes",
          "[foxglove]") {
  const std::uint8_t payload[3] = {0xAA, 0xBB, 0xCC};
  const std::string frame = messageData(0x01020304u, 0x1122334455667788ull, payload, sizeof payload);
  const std::string expected("\x01\x04\x03\x02\x01\x88\x77\x66\x55\x44\x33\x22\x11\xAA\xBB\xCC", 16);
  CHECK(frame == expected);
}

TEST_CASE("a client's subscribe, unsubscribe, advertise, unadvertise and message data are parsed", "[foxglove]") {
  const auto sub = std::get<Subscribe>(parseText(R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":4},{"id":1,"channelId":9}]})"));
  CHECK(sub.subscriptions == std::vector<std::pair<std::uint32_t, std::uint32_t>>{{0, 4}, {1, 9}});
  CHECK(std::get<Unsubscribe>(parseText(R"({"op":"unsubscribe","subscriptionIds":[1]})")).subscription_ids ==
        std::vector<std::uint32_t>{1});
  const auto ad = std::get<ClientAdvertise>(parseText(
      R"({"op":"advertise","channels":[{"id":2,"topic":"flatsat/fault_cmd","encoding":"cdr","schemaName":"flatsat::msg::FaultCmd"}]})"));
  REQUIRE(ad.channels.size() == 1);
  CHECK(ad.channels[0].id == 2);
  CHECK(ad.channels[0].topic == "flatsat/fault_cmd");
  CHECK(std::get<ClientUnadvertise>(parseText(R"({"op":"unadvertise","channelIds":[2]})")).channel_ids ==
        std::vector<std::uint32_t>{2});
  const auto data = std::get<ClientMessageData>(parseBinary(std::string("\x01\x02\x00\x00\x00\x10\x20", 7)));
  CHECK(data.channel_id == 2);
  CHECK(data.data == std::vector<std::uint8_t>{0x10, 0x20});
}

TEST_CASE("a malformed client message is refused with what is wrong with it", "[foxglove]") {
  CHECK_THROWS_WITH(parseText("{not json"), Catch::StartsWith("not JSON"));
  CHECK_THROWS_WITH(parseText("[1,2]"), Catch::Contains("must be a JSON object"));
  CHECK_THROWS_WITH(parseText(R"({"subscriptions":[]})"), Catch::Contains("no field 'op'"));
  CHECK_THROWS_WITH(parseText(R"({"op":"teleport"})"), Catch::Contains("'teleport' is not supported"));
  CHECK_THROWS_WITH(parseText(R"({"op":"subscribe"})"), Catch::Contains("no field 'subscriptions'"));
  CHECK_THROWS_WITH(parseText(R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":2}]})"),
                    Catch::Contains("'id' must be an integer"));
  CHECK_THROWS_WITH(parseText(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":4294967296}]})"),
                    Catch::Contains("'channelId' must be an integer"));
  CHECK_THROWS_WITH(parseText(R"({"op":"advertise","channels":[{"id":1,"topic":3,"encoding":"cdr","schemaName":"x"}]})"),
                    Catch::Contains("'topic' must be a string"));
  CHECK_THROWS_WITH(parseText(R"({"op":"unsubscribe","subscriptionIds":[1,"2"]})"),
                    Catch::Contains("'subscriptionIds' must hold integers"));
  CHECK_THROWS_WITH(parseText(R"({"op":"unadvertise","channelIds":[4294967296]})"),
                    Catch::Contains("'channelIds' must hold integers"));
  CHECK_THROWS_WITH(parseBinary(""), Catch::Contains("empty"));
  CHECK_THROWS_WITH(parseBinary(std::string("\x02\x00", 2)), Catch::Contains("binary opcode 2"));
  CHECK_THROWS_WITH(parseBinary(std::string("\x01\x00\x00", 3)), Catch::Contains("shorter than its 5-byte head"));
}

TEST_CASE("subscriptions are kept per client, and a taken or unknown id is refused", "[foxglove]") {
  Subscriptions<int> subs;
  subs.add(1, 0, 7);
  subs.add(2, 0, 7);  // the same id is another client's own
  subs.add(1, 1, 8);
  CHECK(subs.of(7) == std::vector<std::pair<int, std::uint32_t>>{{1, 0}, {2, 0}});
  CHECK_THROWS_WITH(subs.add(1, 0, 9), Catch::Contains("already in use"));
  CHECK_THROWS_WITH(subs.remove(2, 5), Catch::Contains("no subscription 5"));
  subs.remove(1, 0);
  CHECK(subs.of(7) == std::vector<std::pair<int, std::uint32_t>>{{2, 0}});
  subs.forget(2);
  CHECK(subs.of(7).empty());
  CHECK(subs.of(8).size() == 1);
}

TEST_CASE("health becomes a status: failed or lost is an error, a completed run's end is information",
          "[foxglove]") {
  const ComponentCondition running{"RUNNING", true, "stepping"};
  const auto first = conditionChange("gyro", std::nullopt, running);
  REQUIRE(first);
  CHECK(first->first == StatusLevel::kInfo);
  CHECK(first->second == "gyro RUNNING: stepping");
  CHECK_FALSE(conditionChange("gyro", running, running));  // nothing changed: nothing said
  // A process that is gone is not RUNNING.
  const auto lost = conditionChange("gyro", running, {"RUNNING", false, "stepping"});
  REQUIRE(lost);
  CHECK(lost->first == StatusLevel::kError);
  CHECK(lost->second.rfind("gyro lost while RUNNING", 0) == 0);
  // A completed run is not an alarm, also once its processes have gone.
  const ComponentCondition stopped{"STOPPED", true, "stopped after 450 steps"};
  CHECK(conditionChange("gyro", running, stopped)->first == StatusLevel::kInfo);
  const auto gone = conditionChange("gyro", stopped, {"STOPPED", false, "stopped after 450 steps"});
  CHECK(gone->first == StatusLevel::kInfo);
  CHECK(gone->second == "gyro stopped and has gone");
  CHECK(conditionChange("gyro", running, {"FAILED", true, "no field"})->first == StatusLevel::kError);
}
