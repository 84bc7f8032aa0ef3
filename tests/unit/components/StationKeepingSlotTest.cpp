// SPDX-License-Identifier: Apache-2.0
// Seed S3's slot is one key, orbit.station_longitude_deg: the satellite
// starts over it and station keeping holds it; the planner's old key is
// refused with the new one's name.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>

#include "components/Registry.hpp"
#include "components/station_keeping/StationKeepingNode.hpp"
#include "vehicle/VehicleReader.hpp"

using namespace flatsat;

namespace {

/// geo_nominal.yaml with `keys` laid over it, in a folder of this process's own.
struct OverGeo {
  std::filesystem::path dir = std::filesystem::temp_directory_path() / ("slot-" + std::to_string(::getpid()));
  OverGeo() { std::filesystem::create_directories(dir); }
  ~OverGeo() { std::filesystem::remove_all(dir); }
  bus::Scenario load(const std::string& keys) const {
    const auto file = dir / "slot.yaml";
    std::ofstream(file) << "base: " << FLATSAT_SOURCE_DIR << "/deploy/scenarios/geo_nominal.yaml\n" << keys;
    return bus::loadScenario(file.string());
  }
};

}  // namespace

TEST_CASE("S3: station keeping holds the slot of orbit.station_longitude_deg", "[station_keeping][s3]") {
  const OverGeo over;
  const auto scenario = over.load("orbit: {station_longitude_deg: 19.2}\n");
  REQUIRE(checkScenario(scenario, ".").empty());
  bus::ConfigProblems problems;
  const auto vehicle = vehicle::readVehicle(scenario, problems);
  const auto params = station_keeping::readParams(scenario, vehicle, {scenario.file, "station_keeping", ""}, problems);
  REQUIRE(problems.empty());
  CHECK(params.planner.station_longitude_rad == Approx(19.2 * M_PI / 180.0));

  const auto old_key = over.load("components: {station_keeping: {station_longitude_rad: 75 deg}}\n");
  const auto refused = checkScenario(old_key, ".");
  REQUIRE(refused.size() == 1);
  CHECK(refused[0].find("components.station_keeping.station_longitude_rad: moved to the vehicle's description: give "
                        "it as orbit.station_longitude_deg") != std::string::npos);

  const auto no_slot = over.load("orbit: {station_longitude_deg: null, mean_anomaly_rad: 175 deg}\n");
  const auto missing = checkScenario(no_slot, ".");
  REQUIRE(missing.size() == 1);
  CHECK(missing[0].find("components.station_keeping: needs a slot to hold: orbit.station_longitude_deg") !=
        std::string::npos);
}
