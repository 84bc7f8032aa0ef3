// SPDX-License-Identifier: Apache-2.0
#include "tools/ReportErrors.hpp"
#include "tools/CmdCommand.hpp"

#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <random>

#include "bus/BusFaults.hpp"
#include "bus/Endpoints.hpp"
#include "bus/Shutdown.hpp"
#include "bus/Stamp.hpp"
#include "tools/CommandChecks.hpp"
#include "tools/ToolBus.hpp"

namespace flatsat::tools {

namespace {

constexpr const char* kSender = "flatsat-cmd";  // header.source of every command

struct CmdOptions {
  std::string mode;
  std::string target, kind, key, topic;
  int channel = -1;
  double magnitude = 0.0, start_s = 0.0, duration_s = 0.0, value = 0.0;
  double timeout_s = 15.0;
  int domain = -1;
};

const std::map<std::string, msg::MagneticMode> kModes = {
    {"unload", msg::MAGNETIC_UNLOAD},
    {"detumble", msg::MAGNETIC_DETUMBLE},
    {"spin_capture", msg::MAGNETIC_SPIN_CAPTURE}};

constexpr const char* kRecorder = "recorder";  // participant name of the rig's recorder

bool recorderDiscovered(const ToolBus& tool_bus) {
  for (const auto& [prefix, participant] : tool_bus.participants()) {
    if (participant.alive && participant.name == kRecorder) return true;
  }
  return false;
}

/// Writes `command` on `def`'s topic (kept for late joiners while the tool
/// waits: transient-local) and waits for the acknowledgement carrying its id.
template <class Def>
int send(const Def& def, typename Def::Type command, const std::string& what, const CmdOptions& o) {
  if (const auto problem = commandProblem(command); !problem.empty()) {
    std::cerr << "error: " << what << ": " << problem << "\n";
    return 2;
  }
  const auto started = Clock::now();
  ToolBus tool_bus("cmd", o.domain);
  const std::uint64_t id = std::random_device{}() * 0x100000000ULL + std::random_device{}();
  command.command_id(id);
  bus::setText(command.header().source(), kSender);
  std::mutex mutex;
  std::condition_variable arrived;
  std::optional<msg::CommandAck> ack;
  bus::ReaderOf<bus::topics::kCommandAck> acks(
      tool_bus.bus(), bus::topics::kCommandAck, [&](const msg::CommandAck& a, const Arrival&) {
        if (a.command_id() != id) return;
        {
          std::lock_guard lock(mutex);
          ack = a;
        }
        arrived.notify_all();
      });
  bus::Writer<Def> writer(tool_bus.bus(), def);
  writer.write(command);
  std::cerr << "flatsat cmd: " << what << " (command " << id << ") on " << def.name
            << ", domain " << tool_bus.domain() << "\n";
  const auto deadline = Clock::now() + std::chrono::duration<double>(o.timeout_s);
  std::unique_lock lock(mutex);
  while (!ack) {
    if (Clock::now() > deadline) {
      std::cerr << "error: no acknowledgement of command " << id << " (" << what << ") within "
                << o.timeout_s << " s: is the component running on domain " << tool_bus.domain()
                << "?\n";
      return 1;
    }
    lock.unlock();
    const bool go_on = sleepUnlessInterrupted(0.05);
    lock.lock();
    if (!go_on) return 1;
  }
  lock.unlock();
  // The component matched this writer, the rig's recorder may not have yet: its
  // participant announces itself 0..3 s late when a first announcement is lost
  // under load. Keep the command on offer (transient-local) until discovery
  // has announced the recorder's reader of this topic (matched as it is
  // announced), or found no recorder; then until every matched reader has it.
  const auto discovery_end = started + std::chrono::duration<double>(kDiscoverySeconds);
  while (!tool_bus.readerDiscovered(std::string(def.name), kRecorder) && Clock::now() < deadline) {
    if (Clock::now() > discovery_end && !recorderDiscovered(tool_bus)) {
      std::cerr << "flatsat cmd: no recorder found on domain " << tool_bus.domain() << " within "
                << kDiscoverySeconds << " s: the command is not recorded\n";
      break;
    }
    if (!sleepUnlessInterrupted(0.05)) break;
  }
  if (Clock::now() >= deadline) {
    std::cerr << "flatsat cmd: the recorder's reader of " << def.name << " was not matched within --timeout: "
              << "the command may not be recorded\n";
  }
  // Discovery announcing a reader runs ahead of this writer matching it: until
  // it has matched every reader announced, "all acknowledged" leaves one out
  // (the recorder's, once in three runs), and the command dies with this process.
  const auto matching_end = Clock::now() + std::chrono::seconds(2);
  while (writer.matchedReaders() < tool_bus.readersDiscovered(std::string(def.name)) && Clock::now() < matching_end && Clock::now() < deadline) {
    if (!sleepUnlessInterrupted(0.01)) break;
  }
  // Each matched reader acknowledges once its own participant matched this
  // writer, which can take a discovery announcement period (3 s) when many
  // join at once: wait for all of them, up to --timeout, never a fixed 2 s.
  while (!writer.waitForAcknowledgments(std::chrono::milliseconds(200))) {
    if (Clock::now() >= deadline || bus::shutdownRequested()) {
      std::cerr << "flatsat cmd: not every reader of " << def.name << " acknowledged the command within --timeout: "
                << "the recorder may not hold it\n";
      break;
    }
  }
  // Acknowledged is received, not yet taken: a reader's unread samples of a
  // writer that leaves may go with it. The writer stays a moment longer.
  sleepUnlessInterrupted(1.0);
  const double t_s = static_cast<double>(ack->header().sim_time_ns()) * 1e-9;
  std::printf("%s: %s by %s at step %llu (t = %.1f s): %s\n", what.c_str(),
              ack->accepted() ? "accepted" : "refused", bus::text(ack->header().source()).c_str(),
              static_cast<unsigned long long>(ack->header().step()), t_s,
              bus::text(ack->reason()).c_str());
  return ack->accepted() ? 0 : 3;
}

std::string shortNumber(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

std::int64_t toNs(double seconds) { return std::llround(seconds * 1e9); }

}  // namespace

CLI::App* addCmdCommand(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CmdOptions>();
  auto* cmd = app.add_subcommand("cmd", "send a mode, fault or parameter command to a running rig");
  cmd->require_subcommand(1);
  cmd->footer(
      "Each command carries a random id; the component that applies it answers on\n"
      "flatsat/command_ack with that id, the step from which the change applies and\n"
      "what it did (or why it refused). The rig's recorder records commands and\n"
      "acknowledgements. Each subcommand takes --domain N and --timeout S.\n"
      "Exit 0 accepted, 3 refused, 1 no acknowledgement in time.");
  const auto common = [&](CLI::App* sub) {
    sub->add_option("--timeout", o->timeout_s, "[s] wait this long for the acknowledgement (default 15)")
        ->check(CLI::PositiveNumber);
    addDomainOption(*sub, o->domain);
  };

  auto* mode = cmd->add_subcommand("mode", "magnetic mode of the unloading controller");
  mode->add_option("mode", o->mode, "unload, detumble or spin_capture")
      ->required()
      ->check(CLI::IsMember({"unload", "detumble", "spin_capture"}));
  common(mode);
  mode->callback([o, &exit_code] {
    runReportingErrors(exit_code, [&] {
      msg::ModeCmd command;
      command.mode(kModes.at(o->mode));
      return send(bus::topics::kUnloadingModeCmd, command, "mode " + o->mode, *o);
    });
  });

  auto* fault = cmd->add_subcommand("fault", "inject a sensor or actuator fault (architecture, \"Faults\")");
  fault->add_option("target", o->target,
                    "sensor component (magnetometer, sun_sensor, gyro, ...), dynamics_server "
                    "for the actuators, or bus for a topic's samples (give --topic)")
      ->required();
  fault->add_option("kind", o->kind,
                    "sensors: stuck, bias, noise, spike, dropout, saturation; dynamics_server: "
                    "wheel_failed, wheel_stuck, wheel_degraded, coil_open, thruster_failed; "
                    "bus: drop, delay, duplicate")
      ->required();
  fault->add_option("--topic", o->topic, "bus faults: the stepped topic, e.g. flatsat/magnetometer");
  fault->add_option("--channel", o->channel,
                    "measurement component (axis, wheel), or wheel, coil axis, thruster; -1 all (default)");
  auto* magnitude = fault->add_option("--magnitude", o->magnitude,
                    "bias, spike, noise 1 sigma or clip level, in the measurement's unit; "
                    "wheel_degraded: the torque fraction left, 0..1; bus drop, duplicate: the fraction "
                    "of samples hit, 0..1 (default 1: every one); bus delay: [s]");
  fault->add_option("--start-s", o->start_s, "[s] simulated time it begins (default 0: at once)")
      ->check(CLI::NonNegativeNumber);
  fault->add_option("--duration-s", o->duration_s, "[s] how long (default 0: for the rest of the run)")
      ->check(CLI::NonNegativeNumber);
  common(fault);
  fault->callback([o, magnitude, &exit_code] {
    if (o->target == bus::kBusFaultTarget && o->kind != "delay" && magnitude->count() == 0) o->magnitude = 1.0;
    runReportingErrors(exit_code, [&] {
      msg::FaultCmd command;
      bus::setText(command.target(), o->target);
      bus::setText(command.kind(), o->kind);
      bus::setText(command.topic(), o->topic);
      command.channel(o->channel);
      command.magnitude(o->magnitude);
      command.start_ns(toNs(o->start_s));
      command.duration_ns(toNs(o->duration_s));
      return send(bus::topics::kFaultCmd, command, "fault " + o->kind + " on " + o->target, *o);
    });
  });

  auto* param = cmd->add_subcommand("param", "change a component's parameter while it runs");
  param->add_option("target", o->target, "component: attitude_controller")->required();
  param->add_option("key", o->key, "key as in the scenario: kp_Nm_per_rad, ...")->required();
  param->add_option("value", o->value, "new value, in the unit the key names")->required();
  common(param);
  param->callback([o, &exit_code] {
    runReportingErrors(exit_code, [&] { return sendParamCommand(o->target, o->key, o->value, o->timeout_s, o->domain); });
  });
  return cmd;
}

int sendParamCommand(const std::string& target, const std::string& key, double value, double timeout_s, int domain) {
  CmdOptions o;
  o.timeout_s = timeout_s;
  o.domain = domain;
  msg::ParamCmd command;
  bus::setText(command.target(), target);
  bus::setText(command.key(), key);
  command.value(value);
  return send(bus::topics::kParamCmd, command, "param " + target + "." + key + " = " + shortNumber(value), o);
}

}  // namespace flatsat::tools
