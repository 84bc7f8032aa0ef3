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
#include "bus/LiveFeed.hpp"
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
  bool from_bus = false;  ///< read the bus even where a recorder's live feed is
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
  explicit Bridge(const FoxgloveOptions& o)
      : domain_(resolveDomain(o.domain)),
        server_(o.address, static_cast<std::uint16_t>(o.port), fg::kSubprotocol,
                {[this](ClientId c) { opened(c); }, [this](ClientId c) { closed(c); },
                 [this](ClientId c, const std::string& text) { received(c, [&] { return fg::parseText(text); }); },
                 [this](ClientId c, const std::string& bytes) { received(c, [&] { return fg::parseBinary(bytes); }); }}) {
    bus::forEachTopic([&](const auto& def) { addChannel(def); });
    if (!o.from_bus) {
      try {
        feed_ = bus::LiveFeedClient::connect(
            bus::liveFeedName(domain_), [this](const std::vector<bus::LiveFrame>& frames) { fromFeed(frames); },
            [this](bool ended, const std::string& why) { feedClosed(ended, why); });
      } catch (const bus::LiveFeedError& e) {
        std::cerr << "flatsat foxglove: " << e.what() << "; reading the bus itself\n";
      }
    }
    on_feed_ = feed_ != nullptr;
    if (!on_feed_) readTheBus();
  }
  ~Bridge() {
    // The feed and the readers stop calling before the server and the state they use go.
    feed_.reset();
    acks_.reset();
    health_.reset();
    std::vector<std::shared_ptr<void>> readers;
    {
      std::lock_guard lock(mutex_);
      closing_ = true;  // no reader is made from here on
      for (auto& [topic, channel] : channels_) readers.push_back(std::move(channel.reader));
    }
    readers.clear();  // unlocked: a callback under way may be waiting for the lock
  }

  std::string source() const {
    return feed_ ? "the recorder's live feed" : "the bus (no recorder of this domain on this host)";
  }
  std::uint32_t domain() const { return domain_; }
  std::uint16_t port() const { return server_.port(); }

  /// Advertises topics that have come alive and reports changed health; the
  /// caller's loop calls it a few times a second.
  void poll() {
    if (feed_closed_) leaveTheFeed();
    std::set<std::string, std::less<>> live;
    std::map<std::string, fg::ComponentCondition> now;
    if (feed_) {
      std::lock_guard lock(health_mutex_);
      now = feed_conditions_;
    } else {
      for (const auto& w : tool_bus_->writers()) {
        if (w.alive) live.insert(w.topic);
      }
      std::lock_guard lock(health_mutex_);
      for (const auto& row : healthTable(health_entries_, *tool_bus_)) {
        now[row["component"].get<std::string>()] = {row["state"].get<std::string>(), row["alive"].get<bool>(),
                                                     row["message"].get<std::string>()};
      }
    }
    std::vector<std::pair<fg::StatusLevel, std::string>> changes;
    for (const auto& [name, condition] : now) {
      const auto before = conditions_.find(name);
      if (auto change = fg::conditionChange(
              name, before == conditions_.end() ? std::nullopt : std::optional(before->second), condition)) {
        changes.push_back(*change);
      }
      conditions_[name] = condition;
    }
    std::vector<fg::Channel> fresh;
    std::lock_guard lock(mutex_);
    changes.insert(changes.end(), feed_closed_said_.begin(), feed_closed_said_.end());
    feed_closed_said_.clear();
    for (auto& [topic, channel] : channels_) {
      if (!channel.advertised && (channel.seen || live.count(topic) != 0)) {
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
    bool seen = false;  ///< a sample came through the live feed
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
        return std::make_shared<bus::Reader<Def>>(toolBus().bus(), def, [this, id](const typename Def::Type& sample, const Arrival&) {
          thread_local std::vector<std::uint8_t> bytes;
          bus::serializeInto<Def>(sample, bytes);
          forward(id, sample.header().sim_time_ns(), bytes.data(), bytes.size());
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

  /// A sample (CDR) to every subscriber of its channel, stamped with simulated
  /// time (as the MCAP export stamps it); samples without (health) take the newest seen.
  void forward(std::uint32_t channel_id, std::int64_t ns, const std::uint8_t* data, std::size_t size) {
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
    for (const auto& [client, subscription] : targets) {
      if (server_.sendBinary(client, fg::messageData(subscription, static_cast<std::uint64_t>(std::max<std::int64_t>(0, ns)),
                                                     data, size))) {
        ++messages_sent_;
      }
    }
  }

  /// On the feed's thread: what the recorder took, a step's batch at a time,
  /// handed to the server's thread as one.
  void fromFeed(const std::vector<bus::LiveFrame>& frames) {
    server_.beginBatch();
    try {
      for (const auto& f : frames) fromFeed(f);
    } catch (...) {
      server_.endBatch();  // an open batch would hold every later message back
      throw;
    }
    server_.endBatch();
  }
  void fromFeed(const bus::LiveFrame& f) {
    if (f.kind == bus::LiveFrameKind::kLiveliness) {
      std::lock_guard lock(health_mutex_);
      if (auto it = feed_conditions_.find(std::string(f.name)); it != feed_conditions_.end()) it->second.alive = f.alive;
      return;
    }
    std::uint32_t id = 0;
    {
      std::lock_guard lock(mutex_);
      const auto channel = channels_.find(f.name);
      if (channel == channels_.end()) return;  // a topic this build does not know
      channel->second.seen = true;
      id = channel->second.channel.id;
    }
    if (f.name == bus::topics::kHealth.name) {
      if (const auto h = decoded<bus::topics::kHealth>(f)) {
        std::lock_guard lock(health_mutex_);
        feed_conditions_[bus::text(h->header().source())] = {std::string(msg::toString(h->state())), true,
                                                             bus::text(h->message())};
      }
    } else if (f.name == bus::topics::kCommandAck.name) {
      if (const auto a = decoded<bus::topics::kCommandAck>(f)) acknowledged(*a);
    }
    forward(id, f.sim_time_ns, f.data, f.size);
  }

  template <const auto& kDef>
  static std::optional<typename std::remove_cvref_t<decltype(kDef)>::Type> decoded(const bus::LiveFrame& f) {
    try {
      return bus::deserialize<std::remove_cvref_t<decltype(kDef)>>(std::vector<std::uint8_t>(f.data, f.data + f.size));
    } catch (const std::runtime_error&) {
      return std::nullopt;  // the recorder took it from the bus checked; a broken one is not passed on as news
    }
  }

  /// On the feed's thread, once: poll() takes it from there (the feed cannot
  /// be destroyed from its own thread).
  void feedClosed(bool ended, const std::string& why) {
    std::vector<std::pair<fg::StatusLevel, std::string>> said;
    said.emplace_back(ended ? fg::StatusLevel::kInfo : fg::StatusLevel::kError,
                      why + "; the bridge reads the bus itself from here on");
    {
      std::lock_guard lock(health_mutex_);
      for (auto& [name, condition] : feed_conditions_) {
        if (condition.state == "STOPPED") {
          condition.alive = false;  // gone with the run
        } else if (ended && condition.alive && condition.state != "FAILED") {
          // The recorder stops with the rig; a component slower to stop is
          // not heard stopping, which is no fault of it.
          said.emplace_back(fg::StatusLevel::kInfo, name + " was " + condition.state +
                                                        " when the recorder stopped; its own stop came later");
        }
      }
    }
    std::lock_guard lock(mutex_);
    feed_closed_said_ = std::move(said);
    feed_closed_ = true;
  }

  /// On the main thread, after the feed closed: the last conditions it gave
  /// are reported, then the bridge reads the bus.
  void leaveTheFeed() {
    feed_closed_ = false;
    poll();  // the feed's last word, while feed_ still selects its conditions
    feed_.reset();
    on_feed_ = false;  // from here a subscription makes its reader; readTheBus() makes the others'
    readTheBus();
  }

  /// Samples, health and acknowledgements from the bus itself: with no
  /// recorder of the domain on this host, or after its feed closed.
  void readTheBus() {
    auto& tool_bus = toolBus();
    health_ = std::make_unique<HealthWatcher>(tool_bus, health_mutex_, health_entries_);
    acks_ = std::make_unique<bus::ReaderOf<bus::topics::kCommandAck>>(
        tool_bus.bus(), bus::topics::kCommandAck, [this](const msg::CommandAck& a, const Arrival&) { acknowledged(a); });
    std::vector<std::uint32_t> watched;
    {
      std::lock_guard lock(mutex_);
      for (const auto& [topic, channel] : channels_) {
        if (!subscriptions_.of(channel.channel.id).empty()) watched.push_back(channel.channel.id);
      }
    }
    for (const auto id : watched) makeReader(id);
  }

  ToolBus& toolBus() {
    std::lock_guard lock(tool_bus_mutex_);
    if (!tool_bus_) tool_bus_ = std::make_unique<ToolBus>("foxglove", static_cast<int>(domain_));
    return *tool_bus_;
  }

  void opened(ClientId client) {
    ++clients_seen_;
    std::vector<fg::Channel> advertised;
    std::lock_guard lock(mutex_);
    clients_.insert(client);
    server_.sendText(client, fg::serverInfo("flatsat", {"clientPublish"}, {"cdr"},
                                            {{"domain", std::to_string(domain_)},
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
      {
        std::lock_guard lock(mutex_);
        const auto topic = topic_of_channel_.find(channel_id);
        if (topic == topic_of_channel_.end() || !channels_.at(topic->second).advertised) {
          throw fg::ProtocolError("subscribe: channel " + std::to_string(channel_id) + " is not advertised");
        }
        subscriptions_.add(client, subscription, channel_id);
      }
      if (!on_feed_) makeReader(channel_id);
    }
  }

  /// The DDS reader of a channel someone subscribes to, unless it has one.
  /// From the server's thread, and from the main one as the feed closes.
  void makeReader(std::uint32_t channel_id) {
    std::lock_guard making(reader_making_mutex_);
    std::function<std::shared_ptr<void>()> make_reader;
    ChannelState* channel = nullptr;
    {
      std::lock_guard lock(mutex_);
      channel = &channels_.at(topic_of_channel_.at(channel_id));
      if (channel->reader || closing_) return;
      make_reader = channel->make_reader;
    }
    // Made, and if not wanted deleted, unlocked: the new reader's first
    // samples may arrive at once, and take the lock.
    auto reader = make_reader();
    std::lock_guard lock(mutex_);
    if (!closing_) channel->reader = std::move(reader);
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
      if (!made) made = std::make_shared<bus::Writer<Def>>(toolBus().bus(), def);
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

  const std::uint32_t domain_;
  std::mutex tool_bus_mutex_;
  std::unique_ptr<ToolBus> tool_bus_;  // made when first needed: a bridge on the feed may never need it
  std::mt19937_64 random_{std::random_device{}()};
  const std::string session_id_ = std::to_string(std::random_device{}());
  std::mutex health_mutex_;
  std::map<std::string, HealthEntry> health_entries_;            // read from the bus
  std::map<std::string, fg::ComponentCondition> feed_conditions_;  // given by the feed
  std::map<std::string, fg::ComponentCondition> conditions_;     // as last reported; poll() only
  std::mutex mutex_;  // what the server's thread, the feed and the readers share
  std::map<std::string, ChannelState, std::less<>> channels_;
  std::map<std::uint32_t, std::string> topic_of_channel_;
  bool closing_ = false;
  std::atomic<bool> on_feed_{false};     // whether the samples come from feed_ (which only the main thread touches)
  std::atomic<bool> feed_closed_{false};
  std::mutex reader_making_mutex_;  // one reader made at a time
  std::vector<std::pair<fg::StatusLevel, std::string>> feed_closed_said_;  // for poll() to send
  std::map<std::string, std::shared_ptr<void>> writers_;
  std::set<ClientId> clients_;
  fg::Subscriptions<ClientId> subscriptions_;
  std::map<ClientId, std::map<std::uint32_t, std::string>> client_channels_;
  std::map<std::uint64_t, ClientId> pending_;  // command id -> the client that sent it
  std::atomic<std::int64_t> newest_ns_{0};
  std::atomic<std::uint64_t> clients_seen_{0}, messages_sent_{0}, refused_{0}, commands_sent_{0};
  fg::WebSocketServer server_;
  std::unique_ptr<HealthWatcher> health_;
  std::unique_ptr<bus::ReaderOf<bus::topics::kCommandAck>> acks_;
  std::unique_ptr<bus::LiveFeedClient> feed_;
};

int serve(const FoxgloveOptions& o) {
  Bridge bridge(o);
  std::cout << "flatsat foxglove: ws://" << o.address << ":" << bridge.port() << " (domain " << bridge.domain()
            << ", from " << bridge.source() << ")\n"
            << std::flush;
  const auto start = Clock::now();
  while (o.seconds <= 0.0 || std::chrono::duration<double>(Clock::now() - start).count() < o.seconds) {
    bridge.poll();
    if (!sleepUnlessInterrupted(0.25, 0.25)) break;
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
  cmd->add_flag("--bus", o->from_bus,
                "read every topic from the bus itself, even where the rig's recorder runs on this host\n"
                "(its live feed costs the rig less, and carries what the recorder accepted)");
  addDomainOption(*cmd, o->domain);
  cmd->footer(
      "Open Foxglove or Lichtblick, \"Open connection\", Foxglove WebSocket, ws://127.0.0.1:PORT.\n"
      "Where the rig's recorder runs on this host, the samples come from its live feed (what it\n"
      "records, every step, at a small part of the cost of reading the bus); else, or with --bus,\n"
      "from the bus. Each live topic is a channel (OMG IDL schema, CDR); samples are stamped\n"
      "with simulated time. Health changes arrive as status messages: a component that failed or went away\n"
      "without stopping is an error, one that stopped is information. Clients may publish the\n"
      "operator commands (flatsat/unloading_mode_cmd, flatsat/fault_cmd, flatsat/param_cmd) in\n"
      "CDR; each is checked as `flatsat cmd` checks its own and its acknowledgement comes back\n"
      "as a status message.");
  cmd->callback([o, &exit_code] { runReportingErrors(exit_code, [&] { return serve(*o); }); });
  return cmd;
}

}  // namespace flatsat::tools
