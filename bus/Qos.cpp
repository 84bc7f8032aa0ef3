// SPDX-License-Identifier: Apache-2.0
#include "bus/Qos.hpp"

namespace flatsat::bus {

namespace dds = eprosima::fastdds::dds;

namespace {

constexpr int kSteppedDepth = 64;       // > components that report StepDone in one step
constexpr int kStateReaderDepth = 64;   // > producers of one state topic

template <class Qos>
void common(Qos& qos, int depth) {
  qos.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
  qos.durability().kind = dds::TRANSIENT_LOCAL_DURABILITY_QOS;
  qos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
  qos.history().depth = depth;
}

}  // namespace

dds::DataWriterQos writerQos(QosKind kind) {
  dds::DataWriterQos qos;
  common(qos, kind == QosKind::kState ? 1 : kSteppedDepth);
  return qos;
}

dds::DataReaderQos readerQos(QosKind kind) {
  dds::DataReaderQos qos;
  common(qos, kind == QosKind::kState ? kStateReaderDepth : kSteppedDepth);
  return qos;
}

}  // namespace flatsat::bus
