// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "bus/Recording.hpp"
#include "bus/Scenario.hpp"
#include "bus/StoredSample.hpp"
#include "components/recorder/SampleFigures.hpp"

namespace flatsat::analysis {

/// What summary.json says of a run's samples, accumulated one sample at a
/// time in the order the recording stores them: by the recorder as it
/// writes, on the recording's writer thread (kept in the meta table,
/// bus::meta::kFigures), or from the file in one pass when that is absent
/// (a crash, a resume, a recording made by hand). The figures are the same
/// either way: each producer's samples come in step order, and a pair of
/// streams (an estimate and the truth of its step) is matched as its
/// second half comes (analysis/StepPairs.hpp).
class RunFigures final : public recorder::SampleFigures {
 public:
  explicit RunFigures(const bus::Scenario& scenario);
  ~RunFigures() override;
  void add(const bus::StoredSample& sample) override;
  /// Names from the bus that are not UTF-8 (a foreign writer's) are kept with U+FFFD, never a throw.
  std::string json() const override {
    return figures().dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
  }
  /// Groups of summary keys by what they judge: "extent", "completion",
  /// "truth", "timing", "ownership", "lateness", "trust", "s0", "magnetic",
  /// "aero", "station_keeping", "estimator", "thruster"; summarize() lays
  /// them out.
  nlohmann::ordered_json figures() const;

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
};

/// The figures of the recording: as its recorder kept them, or computed
/// from it in storage order.
nlohmann::ordered_json recordedFigures(const bus::Scenario& scenario, const bus::Recording& recording);

/// Makes every recorder of this program accumulate RunFigures (recorder::setSampleFiguresFactory).
void recordRunFigures();

}  // namespace flatsat::analysis
