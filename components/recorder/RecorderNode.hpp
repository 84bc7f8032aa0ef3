// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bus/Component.hpp"
#include "bus/LiveFeed.hpp"
#include "bus/NodeMain.hpp"
#include "bus/Recording.hpp"
#include "components/recorder/SampleFigures.hpp"

namespace flatsat::recorder {

struct RecorderParams {
  std::string path;                   // recording file (SQLite), created
  std::uint32_t commit_every_steps = 50;  // [-] steps per transaction, 1..100000
  /// [-] decimation: stores the stepped samples and grants stamped at multiples of
  /// this only (as 42 writes its files at an output interval), 1..100000; the
  /// recorder still waits for every sample. 1: every step.
  std::uint32_t record_every_steps = 1;
  std::map<std::string, std::string> meta;  // about the rig (bus/RecordingMeta.hpp)
  /// The summary's figures, accumulated as samples are stored and kept in the
  /// meta table (bus::meta::kFigures); none: the summary reads them back.
  std::shared_ptr<SampleFigures> figures;
  std::vector<std::string> validate() const;
};

/// Records every stepped topic of the rig as samples arrive. In lockstep it
/// is gated like any component: it reports StepDone(k) only once every
/// sample due at k is stored, so the recording is complete by construction.
/// Health, faults, operator commands with their acknowledgements and the step grants are recorded too,
/// and the rig's schedule and timing go to the meta table: enough for
/// `flatsat replay` to stand in for the rest of the rig around one component.
class RecorderNode final : public bus::Component {
 public:
  RecorderNode(bus::Bus& bus, bus::NodeOptions options, const RecorderParams& params);
  ~RecorderNode() override;

 private:
  void step(const bus::StepContext& ctx) override;
  /// Keeps a fault event of kind "intruder" (the writer's GUID, its participant
  /// as the source, at the step granted when it was seen) for each intruder
  /// not kept yet: the recorder reads every topic. From the step thread, at
  /// each step and as the node goes.
  void storeIntruders();
  std::size_t intruders_stored_ = 0;
  /// Commits the last steps: a launcher on another host summarises the
  /// recording as soon as this recorder reports STOPPED.
  void beforeStopped() override;
  template <class Def>
  void record(const Def& def);
  /// Topics that are not stepped: stored on arrival, never waited for;
  /// `on_liveliness`: their writers' liveliness changes (health's, for the live feed).
  template <class Def>
  std::unique_ptr<bus::Reader<Def>> recordAsItComes(bus::Bus& bus, const Def& def,
                                                    typename bus::Reader<Def>::LivelinessCallback on_liveliness = {});
  void store(const std::string& topic, const msg::SampleHeader& header,
             const std::vector<std::uint8_t>& payload);
  /// A sample to the live feed's watchers, if any, sent with the step; `now`:
  /// the rare topics, sent alone when no step sent anything for a while (a
  /// stalled lockstep rig).
  void feed(const std::string& topic, const msg::SampleHeader& header, const std::vector<std::uint8_t>& payload,
            bool now);
  bool feedWatched() const { return live_feed_ && live_feed_->watched(); }

  /// Resuming (bus::meta::kResumeAfterStep): a sample of a step the recording
  /// holds already is compared with it (counted), not stored. The caller holds recording_mutex_.
  bool recordedAlready(const std::string& topic, const msg::SampleHeader& header,
                       const std::vector<std::uint8_t>& payload);
  /// Under bus faults (bus/BusFaults.hpp): which sample the consuming readers
  /// of each faulted topic hold at this step (flatsat/bus_delivery rows).
  void recordDeliveries(const bus::StepContext& ctx);
  /// The summary's figures so far as JSON; empty when there are none (no
  /// analysis in this program) or they stopped on a sample they could not take.
  std::string figuresJson() const;
  /// Whether a stepped sample or grant stamped `step` goes into the recording.
  bool recorded(std::uint64_t step) const { return step % params_.record_every_steps == 0; }

  RecorderParams params_;
  std::mutex recording_mutex_;  // the step thread and the health callback both insert
  bus::Recording recording_;
  std::unique_ptr<bus::LiveFeedServer> live_feed_;  // before the readers that feed it: it outlives them
  std::unique_ptr<bus::ReaderOf<bus::topics::kHealth>> health_;
  std::unique_ptr<bus::ReaderOf<bus::topics::kFaultCmd>> fault_commands_;
  std::unique_ptr<bus::ReaderOf<bus::topics::kFaultEvent>> fault_events_;
  std::unique_ptr<bus::ReaderOf<bus::topics::kUnloadingModeCmd>> mode_commands_;
  std::unique_ptr<bus::ReaderOf<bus::topics::kParamCmd>> param_commands_;
  std::unique_ptr<bus::ReaderOf<bus::topics::kCommandAck>> acks_;
  std::optional<std::uint64_t> last_grant_;  // in the grant observer only
  std::map<std::string, std::uint32_t> producer_dividers_;  // of every recorded stepped topic
  std::optional<std::uint64_t> resume_after_;  // --resume: steps the recording holds already
  std::uint64_t resume_checked_ = 0, resume_mismatches_ = 0;
  std::chrono::steady_clock::time_point last_commit_ = std::chrono::steady_clock::now();
  std::string figures_failure_;  // why the figures stopped: the summary then reads them back
};

/// components.<name>; the file goes to the run directory (--out).
RecorderParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                          bus::ConfigProblems& problems);

}  // namespace flatsat::recorder
