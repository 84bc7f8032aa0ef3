// SPDX-License-Identifier: Apache-2.0
// A component's checkpoint (bus/Checkpoint.hpp) and the Eigen values in it
// (components/common/StateJson.hpp): what is written is read back, and what
// cannot be used is refused naming the file or key and the reason.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <catch2/catch.hpp>

#include "bus/Checkpoint.hpp"
#include "components/common/StateJson.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

TEST_CASE("a checkpoint reads back what was written, and refuses another component's or a broken one",
          "[bus][checkpoint]") {
  const fs::path dir = fs::temp_directory_path() / ("flatsat-checkpoint-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string file = (dir / "estimator.json").string();
  CHECK_FALSE(bus::readCheckpoint(file, "estimator").has_value());

  const Eigen::Matrix3d m = (Eigen::Matrix3d() << 1, 2, 3, 4, 5, 6, 7, 8, 9.5e-17).finished();
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  const nlohmann::json state{{"m", state_json::matrix(m)}, {"q", state_json::quaternion(q)}};
  bus::writeCheckpoint(file, "estimator", {41, state, 41});
  bus::writeCheckpoint(file, "estimator", {41, state, 42});  // step 42 claimed, not yet done
  CHECK_FALSE(fs::exists(file + ".tmp"));
  const auto checkpoint = bus::readCheckpoint(file, "estimator");
  REQUIRE(checkpoint);
  CHECK(checkpoint->step == 41);
  CHECK(checkpoint->claimed == 42);
  Eigen::Matrix3d back;
  state_json::read(checkpoint->state, "m", back);
  CHECK(back == m);  // bit for bit: JSON numbers round-trip doubles
  CHECK(state_json::readQuaternion(checkpoint->state, "q").coeffs() == q.coeffs());

  Eigen::Vector4d four;
  CHECK_THROWS_WITH(state_json::read(checkpoint->state, "m", four), "m: expected 4 numbers");
  CHECK_THROWS_WITH(state_json::readQuaternion(nlohmann::json{{"q", {0, 0, 0, 0}}}, "q"),
                    "q: not a unit quaternion");
  CHECK_THROWS_WITH(bus::readCheckpoint(file, "sequencer"),
                    file + ": the checkpoint of '\"estimator\"', not of 'sequencer'");
  std::ofstream(file) << R"({"component": "estimator", "step": 4, "state": null, "claimed": 3})";
  CHECK_THROWS_WITH(bus::readCheckpoint(file, "estimator"),
                    file + ": not a checkpoint: claimed is before step");
  std::ofstream(file) << "{\"component\": \"estimator\", \"step\": 4";  // cut short by a crash of the disk
  CHECK_THROWS_WITH(bus::readCheckpoint(file, "estimator"), Catch::Matchers::StartsWith(file + ": not a checkpoint"));
  fs::remove_all(dir);
}
