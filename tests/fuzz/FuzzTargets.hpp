// SPDX-License-Identifier: Apache-2.0
#pragma once
// Entry points for the fuzzers (libFuzzer, -DFLATSAT_FUZZ=ON with clang) and
// for the replay of their corpus in the normal build (fuzz_corpus_replay).
// Each takes arbitrary bytes and must return normally: a crash, an escaping
// exception of the wrong kind or a broken invariant aborts.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace flatsat::fuzz {

using Entry = void (*)(const std::uint8_t* data, std::size_t size);

/// The bytes as a scenario file: loadScenario() accepts it or throws
/// ScenarioError, nothing else.
void scenario(const std::uint8_t* data, std::size_t size);
/// The bytes as a serial stream into the parser of the magnetometer's description
/// (deploy/devices/magnetometer.yaml): every frame it delivers re-encodes to the
/// bytes it came from.
void magnetometerFrame(const std::uint8_t* data, std::size_t size);
/// The bytes as a FaultCmd payload: dropped if it does not decode, else the
/// sensors' command handler (toSensorFault) accepts only a valid fault.
void faultCommand(const std::uint8_t* data, std::size_t size);
/// The bytes as a ModeCmd payload: dropped if it does not decode, else the
/// unloading controller's handler (commandedMode) yields a known mode or none.
void modeCommand(const std::uint8_t* data, std::size_t size);
/// First byte picks a registry topic, the rest is a payload for its type's
/// deserialiser as the bus registers it (GuardedType): it never throws, and
/// what decodes re-serialises to a payload that decodes to the same sample.
void topicPayload(const std::uint8_t* data, std::size_t size);

struct Target {
  std::string_view name;  // also the corpus folder: tests/fuzz/corpus/<name>
  Entry entry;
};
inline const std::vector<Target>& targets() {
  static const std::vector<Target> all = {{"scenario", scenario},
                                          {"magnetometer_frame", magnetometerFrame},
                                          {"fault_cmd", faultCommand},
                                          {"mode_cmd", modeCommand},
                                          {"topic_payload", topicPayload}};
  return all;
}

}  // namespace flatsat::fuzz
