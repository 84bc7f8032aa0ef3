// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

namespace flatsat::bus {

/// The rig's QoS presets; every endpoint takes one of these, nothing else
/// sets QoS (style guide: "QoS in one place").
enum class QosKind {
  /// Stepped samples (truth, sensors, estimates, commands, grants, done):
  /// reliable, transient-local so a reader that matches late still gets the
  /// samples of the current step, keep-last deep enough for the largest
  /// fan-in of one step (every component's StepDone on one topic).
  kStepped,
  /// Latest state of each producer (health): reliable, transient-local,
  /// the writer keeps its last sample, readers keep one per producer.
  kState,
  /// Commands and events (faults, later modes and parameters): reliable,
  /// transient-local so a late joiner (recorder, tool) sees recent ones,
  /// keep-last 64 on both sides.
  kCommand,
};

eprosima::fastdds::dds::DataWriterQos writerQos(QosKind kind);
eprosima::fastdds::dds::DataReaderQos readerQos(QosKind kind);

}  // namespace flatsat::bus
