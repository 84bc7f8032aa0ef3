// SPDX-License-Identifier: Apache-2.0
#pragma once
// The body of each component's process: scenario, parameters, bus and node,
// run to the end (bus::runNode). Each is defined beside its node, so that the
// node's code is compiled once, there, and a main only calls its component's.
// Returns the exit code: 0 done, 1 failed, 2 bad configuration.

namespace flatsat {
namespace dynamics_server { int runProcess(int argc, char** argv); }
namespace magnetometer { int runProcess(int argc, char** argv); }
namespace sun_sensor { int runProcess(int argc, char** argv); }
namespace gyro { int runProcess(int argc, char** argv); }
namespace wheel_tach { int runProcess(int argc, char** argv); }
namespace estimator { int runProcess(int argc, char** argv); }
namespace attitude_controller { int runProcess(int argc, char** argv); }
namespace unloading_controller { int runProcess(int argc, char** argv); }
namespace recorder { int runProcess(int argc, char** argv); }
namespace device_bridge { int runProcess(int argc, char** argv); }
namespace device_sim { int runProcess(int argc, char** argv); }
namespace thruster_sequencer { int runProcess(int argc, char** argv); }
namespace star_tracker { int runProcess(int argc, char** argv); }
namespace station_keeping { int runProcess(int argc, char** argv); }
}  // namespace flatsat
