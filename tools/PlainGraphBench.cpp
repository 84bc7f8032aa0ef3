// SPDX-License-Identifier: Apache-2.0
#include "tools/PlainGraphBench.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <functional>
#include <cstdio>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <vector>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <spdlog/spdlog.h>

#include "bus/LoopbackQos.hpp"
#include "msg/StepPubSubTypes.h"
#include "tools/BenchPeers.hpp"

namespace flatsat::tools {
namespace {

namespace dds = eprosima::fastdds::dds;

/// Steps before the timed ones: discovery done, the shared-memory segments warm.
constexpr std::uint64_t kWarmupSteps = 50;
/// The master writes step k again when its commands have not come back within this:
/// a sample sent before a reader matched is gone (volatile), as in the bus's
/// TimeMaster; in steady state it never fires.
constexpr auto kRewriteAfter = std::chrono::milliseconds(200);

struct Role {
  const char* name;
  std::vector<const char*> inputs;
  const char* output;
};

/// The rig's shape (MiddlewareBench's bare graph, bus/Topics.hpp's producers).
const std::array<Role, 7> kRoles = {{
    {"magnetometer", {"truth"}, "magnetometer"},
    {"sun_sensor", {"truth"}, "sun_sensor"},
    {"gyro", {"truth"}, "gyro"},
    {"star_tracker", {"truth"}, "star_tracker"},
    {"estimator", {"magnetometer", "sun_sensor", "gyro", "star_tracker"}, "attitude_estimate"},
    {"attitude_controller", {"attitude_estimate"}, "wheel_torque_cmd"},
    {"unloading_controller", {"attitude_estimate"}, "dipole_cmd"},
}};

/// One process's participant, its inputs and its output. `on_step(k)` runs, on a Fast
/// DDS thread, when every input has step k (or later) and it has not run for k yet;
/// a repeated input of an older step repeats the newest output (the master's rewrite).
class PlainNode final : public dds::DataReaderListener {
 public:
  PlainNode(std::uint32_t domain, const std::string& name, const std::vector<const char*>& inputs, const char* output)
      : type_(new msg::StepDonePubSubType()) {
    auto* factory = dds::DomainParticipantFactory::get_instance();
    participant_ = factory->create_participant(domain, bus::loopbackParticipantQos(domain, true, true));
    if (participant_ == nullptr) throw std::runtime_error(name + ": no participant on domain " + std::to_string(domain));
    type_.register_type(participant_);
    publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
    subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
    dds::DataWriterQos wq = dds::DATAWRITER_QOS_DEFAULT;
    wq.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
    wq.durability().kind = dds::VOLATILE_DURABILITY_QOS;
    wq.history().kind = dds::KEEP_LAST_HISTORY_QOS;
    wq.history().depth = 8;
    dds::DataReaderQos rq = dds::DATAREADER_QOS_DEFAULT;
    rq.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
    rq.durability().kind = dds::VOLATILE_DURABILITY_QOS;
    rq.history().kind = dds::KEEP_LAST_HISTORY_QOS;
    rq.history().depth = 8;
    writer_ = publisher_->create_datawriter(topic(output), wq);
    latest_.assign(inputs.size(), -1);
    for (const char* input : inputs) readers_.push_back(subscriber_->create_datareader(topic(input), rq, this));
    if (writer_ == nullptr || std::count(readers_.begin(), readers_.end(), nullptr) > 0) {
      throw std::runtime_error(name + ": could not create its endpoints");
    }
  }
  ~PlainNode() override {
    if (participant_ == nullptr) return;
    participant_->delete_contained_entities();
    dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }
  PlainNode(const PlainNode&) = delete;
  PlainNode& operator=(const PlainNode&) = delete;

  void write(std::uint64_t step) {
    msg::StepDone sample;
    sample.header().step(step);
    writer_->write(&sample);
    {
      std::lock_guard lock(mutex_);
      written_ = std::max(written_, static_cast<std::int64_t>(step));
    }
    changed_.notify_all();
  }
  /// Waits until every input has reached `step` (the master), or until this node has
  /// written its output of `step` (a relay), or the timeout passed.
  bool waitForInputs(std::uint64_t step, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] {
      return *std::min_element(latest_.begin(), latest_.end()) >= static_cast<std::int64_t>(step);
    });
  }
  bool waitForWritten(std::uint64_t step, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] { return written_ >= static_cast<std::int64_t>(step); });
  }
  std::function<void(std::uint64_t)> on_step;
  dds::DataWriter* writer() { return writer_; }

 private:
  dds::Topic* topic(const std::string& name) {
    const std::string full = "plain/" + name;
    if (auto* found = dynamic_cast<dds::Topic*>(participant_->lookup_topicdescription(full))) return found;
    return participant_->create_topic(full, type_.get_type_name(), dds::TOPIC_QOS_DEFAULT);
  }

  void on_data_available(dds::DataReader* reader) override {
    const std::size_t input = static_cast<std::size_t>(std::find(readers_.begin(), readers_.end(), reader) - readers_.begin());
    msg::StepDone sample;
    dds::SampleInfo info;
    std::int64_t due = -1;
    bool repeat = false;
    {
      std::lock_guard lock(mutex_);
      while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
        if (!info.valid_data) continue;
        const auto step = static_cast<std::int64_t>(sample.header().step());
        repeat = repeat || step <= done_;
        latest_[input] = std::max(latest_[input], step);
      }
      const std::int64_t all = *std::min_element(latest_.begin(), latest_.end());
      if (all > done_) {
        due = done_ = all;
      } else if (repeat && done_ >= 0) {
        due = done_;
      }
    }
    changed_.notify_all();
    if (due >= 0 && on_step) on_step(static_cast<std::uint64_t>(due));
  }

  dds::TypeSupport type_;
  dds::DomainParticipant* participant_ = nullptr;
  dds::Publisher* publisher_ = nullptr;
  dds::Subscriber* subscriber_ = nullptr;
  dds::DataWriter* writer_ = nullptr;
  std::vector<dds::DataReader*> readers_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<std::int64_t> latest_;
  std::int64_t done_ = -1;     // the newest step all inputs reached, relayed
  std::int64_t written_ = -1;  // the newest step written
};

/// The master in this process: truth of step k out, both commands of step k back.
double runMaster(std::uint32_t domain, std::uint64_t steps) {
  PlainNode master(domain, "plain-master", {"wheel_torque_cmd", "dipole_cmd"}, "truth");
  const auto deadline = std::chrono::steady_clock::now() + kPeerTimeout;
  std::chrono::steady_clock::time_point first, last;
  for (std::uint64_t k = 0; k <= steps; ++k) {
    master.write(k);
    while (!master.waitForInputs(k, kRewriteAfter)) {
      if (std::chrono::steady_clock::now() > deadline) {
        throw std::runtime_error("plain graph: step " + std::to_string(k) + " did not come back within " +
                                 std::to_string(kPeerTimeout.count()) + " s");
      }
      master.write(k);
    }
    if (k == kWarmupSteps) first = std::chrono::steady_clock::now();
  }
  last = std::chrono::steady_clock::now();
  return static_cast<double>(steps - kWarmupSteps) / std::chrono::duration<double>(last - first).count();
}

}  // namespace

bool isPlainRole(const std::string& role) {
  return std::any_of(kRoles.begin(), kRoles.end(), [&](const Role& r) { return role == r.name; });
}

int runPlainNode(const std::string& role, std::uint32_t domain, std::uint64_t steps) {
  spdlog::set_level(spdlog::level::warn);
  try {
    const auto found = std::find_if(kRoles.begin(), kRoles.end(), [&](const Role& r) { return role == r.name; });
    if (found == kRoles.end()) throw std::invalid_argument("no role '" + role + "'");
    PlainNode node(domain, role, found->inputs, found->output);
    // Relays on the Fast DDS thread that delivered the last input: the plain way.
    node.on_step = [&node](std::uint64_t step) { node.write(step); };
    // Done once it wrote its output of the last step and that is acknowledged.
    if (!node.waitForWritten(steps, std::chrono::duration_cast<std::chrono::milliseconds>(kPeerTimeout))) {
      spdlog::error("bench-plain {}: step {} never came within {} s", role, steps, kPeerTimeout.count());
      return 1;
    }
    node.writer()->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(5, 0));
    return 0;
  } catch (const std::exception& e) {
    spdlog::error("bench-plain {}: {}", role, e.what());
    return 1;
  }
}

double measurePlainGraphStepsPerSecond(bool quick) {
  const std::uint64_t steps = quick ? 1000 : 3000;
  const std::uint32_t domain = benchDomain();
  try {
    Peers peers;
    for (const Role& role : kRoles) {
      peers.start({"bench-plain", role.name, "--domain", std::to_string(domain), "--steps", std::to_string(steps)});
    }
    const double steps_per_s = runMaster(domain, steps);
    peers.join();
    return steps_per_s;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: plain_graph_steps_per_s: %s\n", e.what());
    return std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace flatsat::tools
