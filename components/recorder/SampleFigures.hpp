// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <functional>
#include <memory>
#include <string>

#include "bus/Scenario.hpp"
#include "bus/StoredSample.hpp"

namespace flatsat::recorder {

/// What a recorder accumulates of the samples it stores, as it stores them,
/// for the run's summary: analysis::RunFigures, installed by the programs
/// that link the analysis (which links every component, the recorder too).
class SampleFigures {
 public:
  virtual ~SampleFigures() = default;
  /// One stored sample, in storage order; throws when it cannot be taken.
  virtual void add(const bus::StoredSample& sample) = 0;
  /// The figures as JSON text (bus::meta::kFigures).
  virtual std::string json() const = 0;
};

using SampleFiguresFactory = std::function<std::unique_ptr<SampleFigures>(const bus::Scenario&)>;

/// Set once, before any recorder is made, by a program that links the analysis.
void setSampleFiguresFactory(SampleFiguresFactory factory);
/// The figures for `scenario`, or nothing when no factory is set.
std::unique_ptr<SampleFigures> makeSampleFigures(const bus::Scenario& scenario);

}  // namespace flatsat::recorder
