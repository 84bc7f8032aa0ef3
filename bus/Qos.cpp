// SPDX-License-Identifier: Apache-2.0
#include "bus/Qos.hpp"

namespace flatsat::bus {

namespace dds = eprosima::fastdds::dds;

namespace {

constexpr int kSteppedDepth = 64;       // > components that report StepDone in one step
constexpr int kStateReaderDepth = 64;   // > producers of one state topic

template <class Qos>
void common(Qos& qos, int depth, const QosTuning& tuning) {
  if (!tuning.data_sharing) qos.data_sharing().off();
  qos.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
  qos.durability().kind = dds::TRANSIENT_LOCAL_DURABILITY_QOS;
  qos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
  qos.history().depth = depth;
}

template <class Qos>
void stepped(Qos& qos, const QosTuning& tuning) {
  qos.ownership().kind = dds::EXCLUSIVE_OWNERSHIP_QOS;
  if (!tuning.watch_liveliness) return;
  qos.deadline().period = ddsDuration(tuning.lease);
  qos.liveliness().kind = dds::MANUAL_BY_TOPIC_LIVELINESS_QOS;
  qos.liveliness().lease_duration = ddsDuration(tuning.lease);
}

template <class Qos>
void state(Qos& qos) {
  qos.liveliness().kind = dds::MANUAL_BY_TOPIC_LIVELINESS_QOS;
  qos.liveliness().lease_duration = ddsDuration(kHealthLease);
}

}  // namespace

eprosima::fastrtps::Duration_t ddsDuration(std::chrono::nanoseconds duration) {
  return {static_cast<int32_t>(duration.count() / 1'000'000'000),
          static_cast<uint32_t>(duration.count() % 1'000'000'000)};
}

dds::DataWriterQos writerQos(QosKind kind, const QosTuning& tuning) {
  dds::DataWriterQos qos;
  common(qos, kind == QosKind::kState ? 1 : kSteppedDepth, tuning);
  if (kind == QosKind::kState) state(qos);
  // A reliable reader acknowledges when a heartbeat asks (Fast DDS's default
  // period: 3 s). An operator tool holds its command on offer until the rig's
  // recorder acknowledged it, and a component its last samples and StepDone
  // until their readers did (over UDP that took up to the 3 s, and the rig's
  // end with it): 0.1 s lets either go within about that of the
  // acknowledgement. A writer sends heartbeats only while a sample is
  // unacknowledged.
  qos.reliable_writer_qos().times.heartbeatPeriod = {0, 100'000'000};
  if (kind == QosKind::kStepped) {
    stepped(qos, tuning);
    qos.ownership_strength().value = static_cast<uint32_t>(tuning.ownership_strength);
  }
  return qos;
}

dds::DataReaderQos readerQos(QosKind kind, const QosTuning& tuning, bool watch_liveliness) {
  dds::DataReaderQos qos;
  common(qos, kind == QosKind::kState ? kStateReaderDepth : kSteppedDepth, tuning);
  if (kind == QosKind::kState && watch_liveliness) state(qos);
  if (kind == QosKind::kStepped) stepped(qos, tuning);
  if (tuning.best_effort_readers && (kind == QosKind::kStepped || kind == QosKind::kProtocol)) {
    qos.reliability().kind = dds::BEST_EFFORT_RELIABILITY_QOS;
  }
  return qos;
}

eprosima::fastdds::dds::DataReaderQos watchingQos(QosKind kind, bool watch_liveliness) {
  auto qos = readerQos(kind, {}, watch_liveliness);
  if (kind != QosKind::kState && kind != QosKind::kCommand) {  // stepped streams
    qos.durability().kind = eprosima::fastdds::dds::VOLATILE_DURABILITY_QOS;
    qos.reliability().kind = eprosima::fastdds::dds::BEST_EFFORT_RELIABILITY_QOS;
  }
  return qos;
}

}  // namespace flatsat::bus
