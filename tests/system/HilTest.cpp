// SPDX-License-Identifier: Apache-2.0
// Hardware swap-in: a paced rig whose magnetometer is taken over mid-run by its
// serial bridge (device simulator on a pseudo-terminal), then handed back to
// the emulator when the bridge is SIGKILLed.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <future>
#include <map>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/Background.hpp"
#include "tests/support/Rig.hpp"
#include "tests/support/SensorContract.hpp"

using namespace flatsat;

namespace {

/// Waits until the run into `out` steps (its time master found every component ready),
/// so that a loaded machine's slow start-up is not counted as run time.
void waitUntilStepping(const std::string& out) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(180);
  while (test::readFile(out + "/logs/dynamics_server.log").find("every component ready") == std::string::npos) {
    REQUIRE(std::chrono::steady_clock::now() < deadline);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

}  // namespace

TEST_CASE("a magnetometer bridge takes over mid-run and the emulator takes back when it dies",
          "[device_bridge][system][paced][hil]") {
  const std::string scenario = std::string(FLATSAT_SCENARIO_DIR) + "/hil_magnetometer.yaml";
  const std::string out = test::freshDir("hil");
  // Shorter than the scenario (120 s, bridge at 30 s): the bridge starts 10 s after
  // the launch and is killed 20 s later; the run ends 20 s after that.
  auto run = std::async(std::launch::async, [&] {
    return test::runScenario(scenario, out,
                             "--set duration_s=50 --set 'components.magnetometer_bridge.start_after_s=10 s'", true);
  });
  std::this_thread::sleep_for(std::chrono::seconds(30));
  // [g]: the pattern must not match the shell running pkill itself.
  const auto kill = test::runCommand("pkill -KILL -f 'flatsat-device_brid[g]e .*--name magnetometer_bridge --out " + out + "'");
  REQUIRE(kill.exit_code == 0);
  const auto s = run.get().summary;
  INFO(s.dump(2));

  CHECK(s["mode"] == "paced");
  CHECK(s["roles"]["magnetometer_bridge"] == "bridge");
  CHECK(s["roles"]["magnetometer"] == "emulated");
  CHECK(s["topic_producers"]["flatsat/magnetometer"] ==
        nlohmann::json::array({"magnetometer", "magnetometer_bridge"}));
  const auto& switches = s["ownership_switches"];
  REQUIRE(switches.size() == 2);
  // Bridge alive: its samples win from its first one, at most a sample period
  // (0.1 s; one more for the arrival-time rounding of a real device's sample).
  CHECK(switches[0]["from"] == "magnetometer");
  CHECK(switches[0]["to"] == "magnetometer_bridge");
  CHECK(switches[0]["gap_s"].get<double>() <= 0.2 + 1e-9);
  CHECK(switches[0]["time_s"].get<double>() > 5.0);
  // Bridge SIGKILLed: readers fall back once its liveliness lease (0.5 s) runs out.
  CHECK(switches[1]["from"] == "magnetometer_bridge");
  CHECK(switches[1]["to"] == "magnetometer");
  CHECK(switches[1]["gap_s"].get<double>() <= 0.5 + 0.2 + 1e-9);
  CHECK(switches[1]["time_s"].get<double>() > switches[0]["time_s"].get<double>() + 15.0);
  // The closed loop never noticed (the default rig's usual error is ~0.14 deg).
  CHECK(s["pointing_error_deg_max"].get<double>() < 0.5);

  // The sensor conformance test, bridge side: the bridge's samples keep the
  // magnetometer topic's contract exactly as the emulator's do, and so do the
  // emulator's on either side of the hand-over (the recorder, an exclusive
  // reader, has only the owner's samples).
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -o " + out +
                           "/export -t truth -t magnetometer")
              .exit_code == 0);
  std::map<std::uint64_t, nlohmann::json> truth;
  for (auto& row : test::exportedRows(out + "/export", "truth")) truth[row["header"]["step"]] = row;
  // Split at the recorded switches: the emulator before, the bridge, the emulator after.
  const double take_over_s = switches[0]["time_s"].get<double>(), fall_back_s = switches[1]["time_s"].get<double>();
  std::map<std::string, std::vector<nlohmann::json>> windows;
  for (auto& row : test::exportedRows(out + "/export", "magnetometer")) {
    const std::string source = row["header"]["source"].get<std::string>();
    const double t_s = row["header"]["sim_time_ns"].get<double>() * 1e-9;
    const bool before = t_s < 0.5 * (take_over_s + fall_back_s);  // the emulator's last sample shares the take-over step
    windows[source == "magnetometer_bridge" ? source : source + (before ? " before" : " after")]
        .push_back(row);
  }
  REQUIRE(windows.size() == 3);
  const auto& contract = test::sensorContracts().at("magnetometer");
  for (const auto& [window, samples] : windows) {
    const std::string source = window.substr(0, window.find(' '));
    INFO(window << ": " << samples.size() << " samples from step " << samples.front()["header"]["step"]
                << " (bridge " << take_over_s << " s to " << fall_back_s << " s)");
    CHECK(samples.size() > 50);
    const auto breaches = test::contractBreaches(samples, truth, contract, {source, 0.1, 10.0, 0.25});
    for (const auto& b : breaches) UNSCOPED_INFO(b);
    CHECK(breaches.empty());
  }
  std::filesystem::remove_all(out);
}

TEST_CASE("three described sensors through their serial bridges keep their topics' contracts in the closed loop",
          "[device_bridge][system][paced][hil]") {
  // hil_sensors.yaml: the magnetometer, the gyro and the fine Sun sensor each behind a
  // pseudo-terminal, one generic bridge per device, 2 % of frames corrupted on the line.
  const std::string out = test::freshDir("hil-sensors");
  const auto s = test::runScenario(std::string(FLATSAT_SCENARIO_DIR) + "/hil_sensors.yaml", out, "--set duration_s=30",
                                   true)
                     .summary;
  INFO(s.dump(2));
  CHECK(s["mode"] == "paced");
  // The usual error of the default rig on its emulators is ~0.14 deg at most.
  CHECK(s["pointing_error_deg_max"].get<double>() < 0.5);
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -o " + out +
                           "/export -t truth -t magnetometer -t gyro -t sun_sensor -t health")
              .exit_code == 0);
  std::map<std::uint64_t, nlohmann::json> truth;
  for (auto& row : test::exportedRows(out + "/export", "truth")) truth[row["header"]["step"]] = row;
  for (const std::string sensor : {"magnetometer", "gyro", "sun_sensor"}) {
    const std::string bridge = sensor + "_bridge";
    INFO(sensor);
    CHECK(s["roles"][bridge] == "bridge");
    // The bridge owns the topic from its first sample on: the recorder, an exclusive reader,
    // holds the emulator's samples only before it.
    std::vector<nlohmann::json> bridged;
    for (auto& row : test::exportedRows(out + "/export", sensor)) {
      if (row["header"]["source"] == bridge) bridged.push_back(row);
    }
    CHECK(bridged.size() > 220);  // of 300 steps, less the start-up
    auto contract = test::sensorContracts().at(sensor);
    if (sensor == "sun_sensor") contract.tolerance = 5 * 1.7e-4 + 0.5 / 32000;  // its noise, and half a count
    const auto breaches = test::contractBreaches(bridged, truth, contract, {bridge, 0.1, 10.0, 0.25});
    for (const auto& b : breaches) UNSCOPED_INFO(b);
    CHECK(breaches.empty());
    // Corrupted frames were seen and counted, never published (the contract above holds).
    std::string last_health;
    for (const auto& h : test::exportedRows(out + "/export", "health")) {
      if (h["header"]["source"] == bridge && h["state"] == "RUNNING") last_health = h["message"];
    }
    INFO(last_health);
    long frames = 0, bad_checksum = 0, bad_header = 0, skipped = 0, bad_value = 0, missed = 0;
    REQUIRE(std::sscanf(last_health.c_str(),
                        "frames %ld, bad: check %ld header %ld value %ld, skipped %ld B, missed %ld",
                        &frames, &bad_checksum, &bad_header, &bad_value, &skipped, &missed) == 6);
    CHECK(frames > 220);
    CHECK(bad_checksum + bad_header + skipped > 0);
    CHECK(bad_value == 0);
    CHECK(missed > 0);  // a corrupted frame is a sample lost: the counter says so
  }
  std::filesystem::remove_all(out);
}

TEST_CASE("a flight computer that speaks no DDS flies the rig over serial lines, and its death fails the run",
          "[device_bridge][system][paced][hil]") {
  // hil_flight_computer.yaml: examples/flight_computer reads the emulated sensors' frames
  // and writes wheel-torque and dipole frames; two bridges put those on the bus.
  const std::string scenario = std::string(FLATSAT_SCENARIO_DIR) + "/hil_flight_computer.yaml";
  const std::string out = test::freshDir("hil-fc");
  const auto s = test::runScenario(scenario, out, "--set duration_s=30", true).summary;
  INFO(s.dump(2));
  CHECK(s["roles"]["flight_computer"] == "program");
  CHECK(s["programs"]["flight_computer"]["topics"] ==
        nlohmann::json({{"flatsat/wheel_torque_cmd", "attitude_controller_bridge"},
                        {"flatsat/dipole_cmd", "unloading_controller_bridge"}}));
  // The default rig on its own controllers, paced and on the Sun, holds it to ~0.02 deg.
  CHECK(s["pointing_error_deg_max"].get<double>() < 0.05);
  // The rig's own attitude controller runs beneath the bridge: the bridge's commands won
  // from its first one, and no hand-over back happened.
  const auto& switches = s["ownership_switches"];
  int back = 0;
  for (const auto& sw : switches) back += sw["from"].get<std::string>().ends_with("_bridge") ? 1 : 0;
  CHECK(back == 0);
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -o " + out +
                           "/export -t wheel_torque_cmd -t dipole_cmd")
              .exit_code == 0);
  std::size_t from_board = 0, total = 0;
  for (const auto& row : test::exportedRows(out + "/export", "wheel_torque_cmd")) {
    ++total;
    from_board += row["header"]["source"] == "attitude_controller_bridge" ? 1 : 0;
  }
  CHECK(from_board > 220);  // of 300 steps, less the start-up
  CHECK(from_board + 20 > total);
  std::size_t dipoles = 0;
  for (const auto& row : test::exportedRows(out + "/export", "dipole_cmd")) {
    dipoles += row["header"]["source"] == "unloading_controller_bridge" && row["active"].get<bool>() ? 1 : 0;
  }
  CHECK(dipoles > 220);  // with every wheel command, the law updated at 1 Hz
  // The board's own account: every input decoded, no frame refused.
  std::ifstream log(out + "/logs/flight_computer.log");
  const std::string board((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  INFO(board);
  for (const std::string input : {"magnetometer", "gyro", "sun_sensor", "wheel_tach"}) {
    long good = -1, bad = -1;
    const auto at = board.rfind(" " + input + " ");
    REQUIRE(at != std::string::npos);
    REQUIRE(std::sscanf(board.c_str() + at + input.size() + 2, "%ld good %ld bad", &good, &bad) == 2);
    CHECK(good > 220);
    CHECK(bad == 0);
  }
  std::filesystem::remove_all(out);

  // No emulator stands behind a program: its death mid-run fails the run, naming it.
  // Until then, started 2 deg off the Sun, the board turns the spacecraft towards it: a
  // torque or a dipole of the wrong sign would turn it away.
  const std::string killed = test::freshDir("hil-fc-killed");
  auto run = std::async(std::launch::async, [&] {
    test::exportTestDomain();
    return test::runCommand(test::runLine(scenario, killed, "--set duration_s=60 --set 'initial.sun_offset_rad=2 deg'"));
  });
  waitUntilStepping(killed);
  std::this_thread::sleep_for(std::chrono::seconds(15));
  CHECK(test::runCommand("pkill -KILL -f 'example_flight_compute[r] .*" + killed + "'").exit_code == 0);
  const auto result = run.get();
  INFO(result.output);
  CHECK(result.exit_code != 0);
  CHECK(result.output.find("program 'flight_computer' exited (killed by signal 9) before the run ended") !=
        std::string::npos);
  REQUIRE(test::runCommand(test::kFlatsat + " export " + killed + "/recording.sqlite --json -o " + killed +
                           "/export -t truth")
              .exit_code == 0);
  std::map<std::uint64_t, double> off_sun_deg;  // the Sun's angle from the boresight, body +x
  for (const auto& row : test::exportedRows(killed + "/export", "truth")) {
    off_sun_deg[row["header"]["step"]] = std::acos(std::clamp(row["sun_body_unit"][0].get<double>(), -1.0, 1.0)) * 180.0 / M_PI;
  }
  REQUIRE(off_sun_deg.count(120));
  INFO("off the Sun at 4, 8, 12 s: " << off_sun_deg[40] << ", " << off_sun_deg[80] << ", " << off_sun_deg[120] << " deg");
  CHECK(off_sun_deg[0] == Approx(2.0).margin(1e-6));
  CHECK(off_sun_deg[80] < off_sun_deg[40]);
  CHECK(off_sun_deg[120] < off_sun_deg[80]);
  CHECK(off_sun_deg[120] < 2.0 - 0.04);  // 1.94 deg after 12 s, the board's PD law on this inertia
  std::filesystem::remove_all(killed);

  // A program that cannot start fails the run at once, and the rig started before it is stopped.
  const std::string unstarted = test::freshDir("hil-fc-unstarted");
  test::exportTestDomain();
  const auto refused = test::runCommand(test::runLine(
      scenario, unstarted,
      "--set duration_s=20 --set 'programs=[{name: flight_computer, command: [no_such_board], "
      "bridges: [attitude_controller_bridge, unloading_controller_bridge]}]'"));
  INFO(refused.output);
  CHECK(refused.exit_code != 0);
  CHECK(refused.output.find("program 'flight_computer' could not be started: cannot start no_such_board") !=
        std::string::npos);
  CHECK(test::runCommand("pgrep -f -- 'flatsat-[a-z_]* .*--out " + unstarted + "'").exit_code == 1);
  std::filesystem::remove_all(unstarted);
}

TEST_CASE("a reaction wheel unit on a serial line turns the plant's wheels, and when it dies the commands do",
          "[device_bridge][system][paced][hil]") {
  // hil_reaction_wheel.yaml: the attitude controller's torques go to a unit stand-in
  // (50 ms, 0.05 N m) as command frames; its answers are the wheel speeds the plant follows.
  const std::string out = test::freshDir("hil-rw");
  auto run = std::async(std::launch::async, [&] {
    return test::runScenario(std::string(FLATSAT_SCENARIO_DIR) + "/hil_reaction_wheel.yaml", out,
                             "--set duration_s=30", true);
  });
  waitUntilStepping(out);
  std::this_thread::sleep_for(std::chrono::seconds(18));
  REQUIRE(test::runCommand("pkill -KILL -f 'flatsat-device_si[m] .*--name wheel_tach_device --out " + out + "'")
              .exit_code == 0);
  const auto s = run.get().summary;
  INFO("ownership_switches: " << s["ownership_switches"].dump());  // first: a long summary is cut in CI's log
  INFO(s.dump(2));
  CHECK(s["roles"]["wheel_tach_bridge"] == "bridge");
  // The default rig's usual error on the Sun, paced, is ~0.02 deg (hil_flight_computer).
  CHECK(s["pointing_error_deg_max"].get<double>() < 0.05);
  const auto& switches = s["ownership_switches"];
  REQUIRE(switches.size() == 2);
  CHECK(switches[0]["to"] == "wheel_tach_bridge");
  CHECK(switches[1]["from"] == "wheel_tach_bridge");
  CHECK(switches[1]["gap_s"].get<double>() <= 0.5 + 0.2 + 1e-9);  // the lease, and a step
  const double lost_s = switches[1]["time_s"].get<double>();
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -o " + out +
                           "/export -t truth -t wheel_tach -t wheel_torque_cmd")
              .exit_code == 0);
  std::map<std::uint64_t, nlohmann::json> truth;
  for (auto& row : test::exportedRows(out + "/export", "truth")) truth[row["header"]["step"]] = row;
  std::map<std::uint64_t, nlohmann::json> answers;
  for (auto& row : test::exportedRows(out + "/export", "wheel_tach")) {
    if (row["header"]["source"] == "wheel_tach_bridge") answers[row["header"]["step"]] = row;
  }
  CHECK(answers.size() > 150);  // of some 180 steps before the unit was killed, less the start-up
  // The steps the unit drove: the server names each change at the step k whose advance
  // makes truth k + 1.
  const std::string server = test::readFile(out + "/logs/dynamics_server.log");
  std::map<std::uint64_t, bool> unit_drives_from;
  const std::regex change("step ([0-9]+): (the wheels follow|no fresh speeds)");
  for (std::sregex_iterator it(server.begin(), server.end(), change), end; it != end; ++it) {
    unit_drives_from[std::stoull((*it)[1]) + 1] = (*it)[2] == "the wheels follow";
  }
  // While the unit drives them, the plant's rotors are where the unit says they are (to its
  // f32 telemetry): the unit, not the command, turned them. Each step follows its own
  // answer or, when that came late (a loaded machine), the newest that had come, which the
  // truth names by its age.
  std::map<std::uint64_t, std::int64_t> followed_age;  // truth step -> the age of the answer it followed
  for (const auto& [step, plant] : truth) {
    const auto governing = unit_drives_from.upper_bound(step);
    if (governing == unit_drives_from.begin() || !std::prev(governing)->second) continue;
    const auto age = plant["wheel_cmd_age_steps"].get<std::int64_t>();
    INFO("truth of step " << step << ", following an answer " << age << " steps old");
    const auto answer = answers.find(step - static_cast<std::uint64_t>(age));
    REQUIRE(answer != answers.end());
    followed_age[step] = age;
    for (std::size_t w = 0; w < 4; ++w) {
      const double unit = answer->second["wheel_speed_rad_s"][w].get<double>(),
                   turned = plant["wheel_speed_rad_s"][w].get<double>();
      CHECK(std::abs(unit - turned) <= 1e-6 * std::max(1.0, std::abs(unit)));
    }
  }
  const auto on_time = std::count_if(followed_age.begin(), followed_age.end(), [](auto f) { return f.second == 0; });
  INFO(on_time << " of " << followed_age.size() << " steps followed their own step's answer");
  CHECK(followed_age.size() > 150);
  // No rotor ever moves faster than the torques asked of it allow: not while following the
  // unit (a rotor mapped to the wrong wheel, or followed with the wrong sign, would jump),
  // nor when the commands take over from where the unit left them (0.1 s steps, 0.12 kg m^2).
  // A step into a late answer, or back to the unit after a silence, is not bounded so: the
  // unit turns on the wall clock, for as long as its answer took.
  double largest_asked = 0.0;
  std::size_t commanded_after = 0;
  for (const auto& row : test::exportedRows(out + "/export", "wheel_torque_cmd")) {
    for (std::size_t w = 0; w < 4; ++w) largest_asked = std::max(largest_asked, std::abs(row["torque_Nm"][w].get<double>()));
    commanded_after += row["header"]["sim_time_ns"].get<double>() * 1e-9 > lost_s + 1.0 ? 1 : 0;
  }
  CHECK(commanded_after > 60);
  double largest_step = 0.0;
  for (auto it = truth.begin(); std::next(it) != truth.end(); ++it) {
    const auto from = followed_age.find(it->first), to = followed_age.find(std::next(it)->first);
    if (to != followed_age.end() && (to->second > 0 || from == followed_age.end() || from->second > 0)) continue;
    for (std::size_t w = 0; w < 4; ++w) {
      largest_step = std::max(largest_step, std::abs(std::next(it)->second["wheel_speed_rad_s"][w].get<double>() -
                                                     it->second["wheel_speed_rad_s"][w].get<double>()));
    }
  }
  INFO("largest torque asked " << largest_asked << " N m");
  CHECK(largest_step <= 2.0 * largest_asked / 0.12 * 0.1 + 1e-6);  // two steps' worth: an answer's jitter
  CHECK(server.find("the wheels follow the unit behind wheel_tach_bridge") != std::string::npos);
  CHECK(server.find("no fresh speeds from wheel_tach_bridge: the commanded torques drive the wheels") != std::string::npos);
  std::filesystem::remove_all(out);
}

TEST_CASE("a reaction wheel unit's rig is refused at validation when its parts do not fit, saying which and why",
          "[device_bridge][system][hil]") {
  const std::string dir = test::freshDir("hil-rw-invalid");
  std::filesystem::create_directories(dir);
  const auto problemsOf = [&](const std::string& name, const std::string& base, const std::string& components) {
    std::ofstream(dir + "/" + name) << "base: " << FLATSAT_SCENARIO_DIR << "/" << base << "\nname: x\ncomponents:\n"
                                    << components;
    const auto result = test::runCommand(test::kFlatsat + " validate " + dir + "/" + name + " 2>&1");
    CHECK(result.exit_code != 0);
    return result.output;
  };
  CHECK_THAT(problemsOf("divider.yaml", "hil_reaction_wheel.yaml", "  wheel_tach: {rate_divider: 2}\n"),
             Catch::Contains("components.wheel_tach.rate_divider: a reaction wheel unit answers every step"));
  CHECK_THAT(problemsOf("unfollowed.yaml", "hil_reaction_wheel.yaml", "  dynamics_server: {wheels_follow: \"\"}\n"),
             Catch::Contains("wheel_tach_bridge commands a reaction wheel unit: set wheels_follow: wheel_tach_bridge"));
  CHECK_THAT(problemsOf("tachometer.yaml", "hil_sensors.yaml",
                        "  dynamics_server: {wheels_follow: wheel_tach_bridge}\n  wheel_tach_bridge: {role: bridge}\n"),
             Catch::Contains("has no command frame): the plant would follow speeds nobody drives"));
  CHECK_THAT(problemsOf("lockstep.yaml", "hil_reaction_wheel.yaml", "  recorder: {}\nmode: lockstep\n"),
             Catch::Contains("wheels_follow: a unit on a serial line runs on the wall clock: needs mode: paced"));
  CHECK_THAT(problemsOf("gyro.yaml", "hil_sensors.yaml", "  gyro_bridge: {role: bridge, protocol: reaction_wheel.yaml}\n"),
             Catch::Contains("'reaction_wheel.yaml' describes frames for flatsat/wheel_tach, which wheel_tach publishes"));
  std::filesystem::remove_all(dir);
}
