// SPDX-License-Identifier: Apache-2.0
// What an operator command must be before `flatsat cmd` or `flatsat foxglove`
// puts it on the bus, whoever composed its bytes.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "tools/CommandChecks.hpp"

using namespace flatsat;

TEST_CASE("an operator command with a field out of its range is not sent, and the field is named", "[tools]") {
  msg::ModeCmd mode;
  mode.mode(msg::MAGNETIC_DETUMBLE);
  CHECK(tools::commandProblem(mode).empty());
  mode.mode(static_cast<msg::MagneticMode>(7));
  CHECK(tools::commandProblem(mode).find("mode 7 is none of") == 0);

  msg::FaultCmd fault;
  bus::setText(fault.target(), "gyro");
  bus::setText(fault.kind(), "bias");
  fault.magnitude(1e-4);
  CHECK(tools::commandProblem(fault).empty());
  fault.magnitude(std::numeric_limits<double>::quiet_NaN());
  CHECK(tools::commandProblem(fault) == "magnitude is not finite");
  fault.magnitude(1e-4);
  fault.start_ns(-1);
  CHECK(tools::commandProblem(fault) == "start_ns is negative");
  fault.start_ns(0);
  fault.channel(-2);
  CHECK(tools::commandProblem(fault).find("channel -2") == 0);
  fault.channel(-1);
  bus::setText(fault.target(), "bus");
  CHECK(tools::commandProblem(fault) == "a bus fault names its topic");
  fault.kind().fill('x');  // no NUL within its 16 chars: as foreign bytes may come
  CHECK(tools::commandProblem(fault).find("kind is not NUL-terminated") == 0);

  msg::ParamCmd param;
  bus::setText(param.target(), "attitude_controller");
  bus::setText(param.key(), "kp_Nm_per_rad");
  param.value(1.5);
  CHECK(tools::commandProblem(param).empty());
  param.value(INFINITY);
  CHECK(tools::commandProblem(param) == "value is not finite");
  bus::setText(param.key(), "");
  CHECK(tools::commandProblem(param) == "key is empty");
  bus::setText(param.key(), "k\x01");
  CHECK(tools::commandProblem(param) == "key holds characters that are not printable");
}
