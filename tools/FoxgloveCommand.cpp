// SPDX-License-Identifier: Apache-2.0
#include "tools/FoxgloveCommand.hpp"

#include <sys/resource.h>

#include <atomic>
#include <iostream>
#include <memory>
#include <mutex>
#include <random>
#include <set>

#include "analysis/McapSchemas.hpp"
#include "bus/Serialization.hpp"
#include "bus/Stamp.hpp"
#include "rig/Spawn.hpp"
#include "tools/CommandChecks.hpp"
#include "tools/HealthTable.hpp"
#include "tools/ReportErrors.hpp"
#include "tools/ToolBus.hpp"
#include "tools/foxglove/FoxgloveProtocol.hpp"
#include "tools/foxglove/WebSocketServer.hpp"

namespace flatsat::tools {

namespace {

namespace fg = foxglove;
using fg::ClientId;

constexpr const char* kBridgeSender = "flatsat-foxglove";  // header.source of the commands it passes on

struct FoxgloveOptions {
  int port = 8765;
  std::string address = "127.0.0.1";
  double seconds = 0.0;  ///< 0: until Ctrl-C
  int domain = -1;
};

/// Whether a client may publish on `def`'s topic: the operator commands only.
template <class Def>
constexpr bool kClientPublishable = std::is_same_v<Def, std::remove_cvref_t<decltype(bus::topics::kUnloadingModeCmd)>> ||
                                    std::is_same_v<Def, std::remove_cvref_t<decltype(bus::topics::kFaultCmd)>> ||
                                    std::is_same_v<Def, std::remove_cvref_t<decltype(bus::topics::kParamCmd)>>;

std::string publishableTopics() {
  std::string names;
  bus::forEachTopic([&](const auto& def) {
    if constexpr (kClientPublishable<std::remove_cvref_t<decltype(def)>>) {
      names += (names.empty() ? "" : ", ") + std::string(def.name);
    }
  });
  return names;
}

double ownCpuSeconds() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return rig::cpuSeconds(usage);
}

class Bridge {
 public:
  Bridge(ToolBus& tool_bus, const FoxgloveOptions& o)
      : tool_bus_(tool_bus),
        health_(tool_bus, health_mutex_, health_entries_),
        server_(o.address, static_cast<std::uint16_t>(o.port), fg::kSubprotocol,
                {[this](ClientId c) { opened(c); }, [this](ClientId c) { closed(c); },
                 [this](ClientId c, const std::string& text) { received(c, [&] { return fg::parseText(text); }); },
                 [this](ClientId c, const std::string& bytes) { received(c, [&] { return fg::parseBinary(bytes); }); }}) {
    bus::forEachTopic([&](const auto& def) { addChannel(def); });
    acks_ = std::make_unique<bus::ReaderOf<bus::topics::kCommandAck>>(
        tool_bus.bus(), bus::topics::kCommandAck, [this](const msg::CommandAck& a, const Arrival&) { acknowledged(a); });
  }
  ~Bridge() {
    // The readers stop calling before the server and the state they use go.
    acks_.reset();
    std::vector<std::shared_ptr<void>> readers;
    {
      std::lock_guard lock(mutex_);
      closing_ = true;  // no reader is made from here on
      for (auto& [topic, channel] : channels_) readers.push_back(std::move(channel.reader));
    }
    readers.clear();  // unlocked: a callback under way may be waiting for the lock
  }

  std::uint16_t port() const { return server_.port(); }

  /// Advertises topics that have come alive and reports changed health; the
  /// caller's loop calls it a few times a second.
  void poll() {
    std::set<std::string> live;
    for (const auto& w : tool_bus_.writers()) {
      if (w.alive) live.insert(w.topic);
    }
    std::vector<fg::Channel> fresh;
    std::vector<std::pair<fg::StatusLevel, std::string>> changes;
    {
      std::lock_guard lock(health_mutex_);
      for (const auto& row : healthTable(health_entries_, tool_bus_)) {
        const auto name = row["component"].get<std::string>();
        const fg::ComponentCondition now{row["state"].get<std::string>(), row["alive"].get<bool>(),
                                         row["message"].get<std::string>()};
        const auto before = conditions_.find(name);
        if (auto change = fg::conditionChange(
                name, before == conditions_.end() ? std::nullopt : std::optional(before->second), now)) {
          changes.push_back(*change);
        }
        conditions_[name] = now;
      }
    }
    std::lock_guard lock(mutex_);
    for (auto& [topic, channel] : channels_) {
      if (!channel.advertised && live.count(topic) != 0) {
        channel.advertised = true;
        fresh.push_back(channel.channel);
      }
    }
    for (const ClientId client : clients_) {
      if (!fresh.empty()) server_.sendText(client, fg::advertise(fresh));
      for (const auto& [level, message] : changes) server_.sendText(client, fg::status(level, message));
    }
  }

  void report(std::ostream& out) const {
    out << "flatsat foxglove: " << clients_seen_.load() << " clients, " << messages_sent_.load() << " messages sent, "
        << server_.backlogDrops() << " missed by slow clients, " << refused_.load() << " client messages refused, "
        << commands_sent_.load() << " commands passed on; cpu_s " << ownCpuSeconds() << "\n";
  }

 private:
  struct ChannelState {
    fg::Channel channel;
    bool advertised = false;
    /// The topic's reader exists only while a client subscribes to it: a bridge
    /// nobody watches costs the rig nothing per sample.
    std::function<std::shared_ptr<void>()> make_reader;
    std::shared_ptr<void> reader;
    /// Checks and writes a client's command on this topic; empty: clients may not publish here.
    std::function<void(ClientId, const std::vector<std::uint8_t>&)> publish;
  };

  template <class Def>
  void addChannel(const Def& def) {
    const std::string type = typename Def::PubSubType().getName();
    const auto idl = analysis::omgIdlSchema(type);
    if (idl.empty()) return;  // no IDL text to describe it with
    std::uint32_t id = 0;
    {
      std::lock_guard lock(mutex_);  // a client may connect while the channels are made
      id = static_cast<std::uint32_t>(channels_.size() + 1);
      // The command topics from the start: a client that publishes needs their schemas.
      auto& channel = channels_[std::string(def.name)];
      channel.channel = {id, std::string(def.name), "cdr", type, std::string(idl), "omgidl"};
      channel.advertised = kClientPublishable<Def>;
      channel.make_reader = [this, id, &def]() -> std::shared_ptr<void> {
        return std::make_shared<bus::Reader<Def>>(tool_bus_.bus(), def, [this, id](const typename Def::Type& sample, const Arrival&) {
          forward<Def>(id, sample);
        });
      };
      topic_of_channel_[id] = std::string(def.name);
      if constexpr (kClientPublishable<Def>) {
        channel.publish = [this, &def](ClientId client, const std::vector<std::uint8_t>& data) {
          publish(def, client, data);
        };
      }
    }
  }

  /// A sample to every subscriber of its channel, stamped with simulated time
  /// (as the MCAP export stamps it); samples without (health) take the newest seen.
  template <class Def>
  void forward(std::uint32_t channel_id, const typename Def::Type& sample) {
    std::int64_t ns = sample.header().sim_time_ns();
    if (ns > 0) {
      std::int64_t seen = newest_ns_.load();
      while (ns > seen && !newest_ns_.compare_exchange_weak(seen, ns)) {
      }
    } else {
      ns = newest_ns_.load();
    }
    std::vector<std::pair<ClientId, std::uint32_t>> targets;
    {
      std::lock_guard lock(mutex_);
      targets = subscriptions_.of(channel_id);
    }
    if (targets.empty()) return;  // nobody listens: no serializing
    thread_local std::vector<std::uint8_t> bytes;
    bus::serializeInto<Def>(sample, bytes);
    for (const auto& [client, subscription] : targets) {
      if (server_.sendBinary(client, fg::messageData(subscription, static_cast<std::uint64_t>(std::max<std::int64_t>(0, ns)),
                                                     bytes.data(), bytes.size()))) {
        ++messages_sent_;
      }
    }
  }

  void opened(ClientId client) {
    ++clients_seen_;
    std::vector<fg::Channel> advertised;
    std::lock_guard lock(mutex_);
    clients_.insert(client);
    server_.sendText(client, fg::serverInfo("flatsat", {"clientPublish"}, {"cdr"},
                                            {{"domain", std::to_string(tool_bus_.domain())},
                                             {"publishable_topics", publishableTopics()}},
                                            session_id_));
    for (const auto& [topic, channel] : channels_) {
      if (channel.advertised) advertised.push_back(channel.channel);
    }
    if (!advertised.empty()) server_.sendText(client, fg::advertise(advertised));
    std::lock_guard health_lock(health_mutex_);
    for (const auto& [name, condition] : conditions_) {
      if (auto now = fg::conditionChange(name, std::nullopt, condition)) {
        server_.sendText(client, fg::status(now->first, now->second));
      }
    }
  }

  void closed(ClientId client) {
    {
      std::lock_guard lock(mutex_);
      clients_.erase(client);
      subscriptions_.forget(client);
      client_channels_.erase(client);
      for (auto it = pending_.begin(); it != pending_.end();) it = it->second == client ? pending_.erase(it) : std::next(it);
    }
    dropUnwatchedReaders();
  }

  /// Deletes the readers of channels nobody subscribes to any more.
  void dropUnwatchedReaders() {
    std::vector<std::shared_ptr<void>> unwatched;
    {
      std::lock_guard lock(mutex_);
      for (auto& [topic, channel] : channels_) {
        if (channel.reader && subscriptions_.of(channel.channel.id).empty()) unwatched.push_back(std::move(channel.reader));
      }
    }
    unwatched.clear();  // unlocked: a callback under way may be waiting for the lock
  }

  /// A client's message, parsed by `parse`; whatever is wrong with it is
  /// answered with an error status, and the connection stays.
  template <class Parse>
  void received(ClientId client, Parse&& parse) {
    try {
      std::visit([&](const auto& request) { handle(client, request); }, parse());
    } catch (const fg::ProtocolError& e) {
      ++refused_;
      server_.sendText(client, fg::status(fg::StatusLevel::kError, e.what()));
    }
  }

  void handle(ClientId client, const fg::Subscribe& s) {
    for (const auto& [subscription, channel_id] : s.subscriptions) {
      std::function<std::shared_ptr<void>()> make_reader;
      ChannelState* channel = nullptr;
      {
        std::lock_guard lock(mutex_);
        const auto topic = topic_of_channel_.find(channel_id);
        if (topic == topic_of_channel_.end() || !channels_.at(topic->second).advertised) {
          throw fg::ProtocolError("subscribe: channel " + std::to_string(channel_id) + " is not advertised");
        }
        subscriptions_.add(client, subscription, channel_id);
        channel = &channels_.at(topic->second);
        if (!channel->reader && !closing_) make_reader = channel->make_reader;
      }
      if (!make_reader) continue;
      // Made unlocked (the new reader's first samples may arrive at once, and
      // take the lock); only this thread makes or drops readers.
      auto reader = make_reader();
      std::lock_guard lock(mutex_);
      if (!closing_) channel->reader = std::move(reader);
    }
  }
  void handle(ClientId client, const fg::Unsubscribe& u) {
    {
      std::lock_guard lock(mutex_);
      for (const auto id : u.subscription_ids) subscriptions_.remove(client, id);
    }
    dropUnwatchedReaders();
  }
  void handle(ClientId client, const fg::ClientAdvertise& a) {
    std::lock_guard lock(mutex_);
    for (const auto& channel : a.channels) {
      const std::string which = "advertise: client channel " + std::to_string(channel.id) + " ('" + channel.topic + "')";
      const auto target = channels_.find(channel.topic);
      if (target == channels_.end() || !target->second.publish) {
        throw fg::ProtocolError(which + ": clients publish only the operator commands: " + publishableTopics());
      }
      if (channel.encoding != "cdr") throw fg::ProtocolError(which + ": encoding '" + channel.encoding + "'; this bridge takes cdr");
      client_channels_[client][channel.id] = channel.topic;
    }
  }
  void handle(ClientId client, const fg::ClientUnadvertise& u) {
    std::lock_guard lock(mutex_);
    for (const auto id : u.channel_ids) {
      if (client_channels_[client].erase(id) == 0) {
        throw fg::ProtocolError("unadvertise: no client channel " + std::to_string(id));
      }
    }
  }
  void handle(ClientId client, const fg::ClientMessageData& m) {
    std::function<void(ClientId, const std::vector<std::uint8_t>&)> publisher;
    {
      std::lock_guard lock(mutex_);
      const auto& mine = client_channels_[client];
      const auto channel = mine.find(m.channel_id);
      if (channel == mine.end()) {
        throw fg::ProtocolError("message data on client channel " + std::to_string(m.channel_id) +
                                ", which this client did not advertise");
      }
      publisher = channels_.at(channel->second).publish;
    }
    publisher(client, m.data);
  }

  /// A client's command, checked as `flatsat cmd` checks its own, then on the
  /// bus with an id of the bridge's; its acknowledgement goes back to that client.
  template <class Def>
  void publish(const Def& def, ClientId client, const std::vector<std::uint8_t>& data) {
    typename Def::Type command;
    try {
      command = bus::deserialize<Def>(data);
    } catch (const std::runtime_error& e) {
      throw fg::ProtocolError(std::string(def.name) + ": " + e.what() + " (CDR with its encapsulation header)");
    }
    if (const auto problem = commandProblem(command); !problem.empty()) {
      throw fg::ProtocolError(std::string(def.name) + ": not sent: " + problem);
    }
    const std::uint64_t id = random_() * 0x100000000ULL + random_();
    command.command_id(id);
    bus::setText(command.header().source(), kBridgeSender);
    std::shared_ptr<bus::Writer<Def>> writer;
    {
      std::lock_guard lock(mutex_);
      pending_[id] = client;
      auto& made = writers_[std::string(def.name)];
      if (!made) made = std::make_shared<bus::Writer<Def>>(tool_bus_.bus(), def);
      writer = std::static_pointer_cast<bus::Writer<Def>>(made);
    }
    // Unlocked: the write reaches this bridge's own reader of the topic at once, which locks.
    writer->write(command);
    ++commands_sent_;
    server_.sendText(client, fg::status(fg::StatusLevel::kInfo,
                                        std::string(def.name) + ": command " + std::to_string(id) + " sent",
                                        "command-" + std::to_string(id)));
  }

  void acknowledged(const msg::CommandAck& a) {
    std::lock_guard lock(mutex_);
    const auto it = pending_.find(a.command_id());
    if (it == pending_.end()) return;
    server_.sendText(it->second, fg::status(a.accepted() ? fg::StatusLevel::kInfo : fg::StatusLevel::kWarning,
                                            "command " + std::to_string(a.command_id()) + " " +
                                                (a.accepted() ? "accepted" : "refused") + " by " +
                                                bus::text(a.header().source()) + " at step " +
                                                std::to_string(a.header().step()) + ": " + bus::text(a.reason()),
                                            "command-" + std::to_string(a.command_id())));
    pending_.erase(it);
  }

  ToolBus& tool_bus_;
  std::mt19937_64 random_{std::random_device{}()};
  const std::string session_id_ = std::to_string(std::random_device{}());
  std::mutex health_mutex_;
  std::map<std::string, HealthEntry> health_entries_;
  std::map<std::string, fg::ComponentCondition> conditions_;
  HealthWatcher health_;
  std::mutex mutex_;  // what the server's thread and the readers' share
  std::map<std::string, ChannelState> channels_;
  std::map<std::uint32_t, std::string> topic_of_channel_;
  bool closing_ = false;
  std::map<std::string, std::shared_ptr<void>> writers_;
  std::set<ClientId> clients_;
  fg::Subscriptions<ClientId> subscriptions_;
  std::map<ClientId, std::map<std::uint32_t, std::string>> client_channels_;
  std::map<std::uint64_t, ClientId> pending_;  // command id -> the client that sent it
  std::atomic<std::int64_t> newest_ns_{0};
  std::atomic<std::uint64_t> clients_seen_{0}, messages_sent_{0}, refused_{0}, commands_sent_{0};
  fg::WebSocketServer server_;
  std::unique_ptr<bus::ReaderOf<bus::topics::kCommandAck>> acks_;
};

int serve(const FoxgloveOptions& o) {
  ToolBus tool_bus("foxglove", o.domain);
  Bridge bridge(tool_bus, o);
  std::cout << "flatsat foxglove: ws://" << o.address << ":" << bridge.port() << " (domain " << tool_bus.domain()
            << ")\n"
            << std::flush;
  const auto start = Clock::now();
  while (o.seconds <= 0.0 || std::chrono::duration<double>(Clock::now() - start).count() < o.seconds) {
    bridge.poll();
    if (!sleepUnlessInterrupted(0.25)) break;
  }
  bridge.report(std::cerr);
  return 0;
}

}  // namespace

CLI::App* addFoxgloveCommand(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<FoxgloveOptions>();
  auto* cmd = app.add_subcommand("foxglove", "serve a running rig to Foxglove or Lichtblick (Foxglove WebSocket)");
  cmd->add_option("--port", o->port, "TCP port (default 8765; 0: any free one, printed)")->check(CLI::Range(0, 65535));
  cmd->add_option("--address", o->address, "address to listen on (default 127.0.0.1: this host only)");
  cmd->add_option("--seconds", o->seconds, "stop after S seconds [s] (default: at Ctrl-C)")->check(CLI::NonNegativeNumber);
  addDomainOption(*cmd, o->domain);
  cmd->footer(
      "Open Foxglove or Lichtblick, \"Open connection\", Foxglove WebSocket, ws://127.0.0.1:PORT.\n"
      "Each live topic is a channel (OMG IDL schema, CDR); samples are stamped with simulated\n"
      "time. Health changes arrive as status messages: a component that failed or went away\n"
      "without stopping is an error, one that stopped is information. Clients may publish the\n"
      "operator commands (flatsat/unloading_mode_cmd, flatsat/fault_cmd, flatsat/param_cmd) in\n"
      "CDR; each is checked as `flatsat cmd` checks its own and its acknowledgement comes back\n"
      "as a status message.");
  cmd->callback([o, &exit_code] { runReportingErrors(exit_code, [&] { return serve(*o); }); });
  return cmd;
}

}  // namespace flatsat::tools
