// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <chrono>
#include <cstdint>

#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

namespace flatsat::bus {

/// The rig's QoS presets; every endpoint takes one of these, nothing else
/// sets QoS (style guide: "QoS in one place").
enum class QosKind {
  /// Stepped data with one logical producer (truth, sensors, estimates,
  /// commands): reliable, transient-local so a reader that matches late
  /// still gets the current step, keep-last deep enough that no writer is
  /// ever more than one step ahead of it, and EXCLUSIVE ownership so a
  /// hardware bridge (high strength) overrides its emulator (low strength)
  /// while it lives (architecture, "Hardware in the loop").
  kStepped,
  /// The step protocol (grant, done): like kStepped but shared ownership,
  /// since every component writes StepDone.
  kProtocol,
  /// Latest state of each producer (health): reliable, transient-local,
  /// the writer keeps its last sample, readers keep one per producer.
  kState,
  /// Commands and events (faults, later modes and parameters): reliable,
  /// transient-local so a late joiner (recorder, tool) sees recent ones,
  /// keep-last 64 on both sides, shared ownership.
  kCommand,
};

/// What differs between the processes of a rig, set once per participant.
struct QosTuning {
  /// Paced rigs detect a silent producer: a deadline and MANUAL_BY_TOPIC
  /// liveliness with `lease` on stepped topics, so exclusive ownership
  /// falls back to the emulator within `lease` when a bridge dies (with
  /// AUTOMATIC liveliness a killed writer would stay "alive" for the 20 s
  /// participant lease).
  bool watch_liveliness = false;
  std::chrono::milliseconds lease{1000};  ///< [ms] deadline and liveliness lease, > 0
  std::int32_t ownership_strength = 10;   ///< [-] emulators 10, hardware bridges 100
  /// Fast DDS's zero-copy data sharing between processes of one host (its
  /// default). Off for processes the launcher may kill and start again
  /// (`flatsat run --restart`): a process SIGKILLed while its writer's pool
  /// was in use left the restarted reader asserting in
  /// ReaderPool::get_payload (Fast DDS 2.9.1, found by the soak, 88 aborts in
  /// a row). Their samples go through the shared-memory transport instead;
  /// peers with data sharing on meet them there.
  bool data_sharing = true;
  /// Stepped readers best effort: no acknowledgement for each sample taken.
  /// A data-sharing reader acknowledges every sample it takes (Fast DDS
  /// 2.9.1, StatefulReader::change_read_by_user), which wakes a thread of the
  /// writer's process: twelve a step for the default rig's recorder.
  /// Lossless only in a lockstep rig whose every writer shares memory with
  /// its readers (the launcher vouches: NodeArgs::shared_memory_rig): a
  /// transient-local data-sharing reader takes a writer's pool history when
  /// it matches, as a reliable one would, and the time master keeps every
  /// component within 15 steps of every writer (bus/StepReports.hpp), well
  /// inside the writers' 64 samples; the time master waits for everyone's
  /// last StepDone before it stops. Over a transport a best-effort sample
  /// can be lost. The grants and StepDones (kProtocol) too: a grant reader
  /// lags no more than a stepped one, and the time master keeps its process,
  /// and the grants' pool, until every component said it stopped
  /// (TimeMaster::waitForStoppedComponents), as the stop grant's
  /// acknowledgements did for a reliable reader.
  bool best_effort_readers = false;
};

/// A chrono duration as a DDS one (QoS periods, waits).
eprosima::fastrtps::Duration_t ddsDuration(std::chrono::nanoseconds duration);

/// Liveliness lease of the health topic: every node asserts it from a thread
/// of its own every third of it (Node), so a reader learns within the lease
/// that a component's process is gone (MANUAL_BY_TOPIC: with AUTOMATIC a
/// killed writer would stay alive for the 20 s participant lease).
inline constexpr std::chrono::milliseconds kHealthLease{3000};

/// A running component whose last health (every second, bus::kHealthPeriod)
/// is older than this is late: its steps have stopped turning though its
/// process may live (paced rigs; the time master records it, `flatsat
/// health` shows it).
inline constexpr std::chrono::milliseconds kHealthLate{1500};

inline constexpr std::int32_t kEmulatorStrength = 10;
inline constexpr std::int32_t kBridgeStrength = 100;

eprosima::fastdds::dds::DataWriterQos writerQos(QosKind kind, const QosTuning& tuning = {});
/// `watch_liveliness`: a state reader that reports its writers' liveliness (a
/// health watcher) asks for the writers' lease; every other state reader asks
/// for none, so Fast DDS tracks no writer for it (bus::Bus::createReader says
/// why that matters). Paced stepped readers always watch (QosTuning).
eprosima::fastdds::dds::DataReaderQos readerQos(QosKind kind, const QosTuning& tuning = {},
                                                bool watch_liveliness = false);
/// A watching reader's QoS (the operator tools: Reader's watching
/// constructor): the preset's, so ownership and the like match the writers,
/// except that stepped topics are read volatile and best-effort. A tool
/// watches the live stream: the writers' history would replay old steps and
/// skew rates, and a best-effort reader never acknowledges, so attaching a
/// tool adds no protocol work to a rig in lockstep. State and command topics
/// keep their transient-local history: the last health of every component is
/// the point.
eprosima::fastdds::dds::DataReaderQos watchingQos(QosKind kind, bool watch_liveliness);

}  // namespace flatsat::bus
