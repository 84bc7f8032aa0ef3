// SPDX-License-Identifier: Apache-2.0
// The live web view: `flatsat web` beside a running rig, the page loaded in
// Debian's headless Chromium, which must show every component of the rig in the
// health table and live truth samples in the plots; a screenshot is kept.
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <thread>

#include "tests/support/Background.hpp"
#include "tests/support/Rig.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

const std::string kChromium = "/usr/bin/chromium";

/// Headless, with nothing reaching beyond this machine (env: the closed network refuses
/// Chromium's own background connections), a fresh profile, the page's timers run 3 s.
std::string chromium(const std::string& profile, const std::string& what) {
  return "timeout 60 " + kChromium +
         " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking"
         " --disable-component-update --disable-sync --user-data-dir=" +
         profile + " --virtual-time-budget=3000 " + what + " 2>/dev/null";
}

}  // namespace

TEST_CASE("the live web view shows every component of a running rig in headless Chromium",
          "[system][tools][web]") {
  if (!fs::exists(kChromium)) {
    WARN("SKIPPED: no " + kChromium + " (deploy/rig.sh test installs Debian's chromium)");
    return;
  }
  const auto domain = test::exportTestDomain();
  const std::string run = test::freshDir("web");
  test::Background rig(test::kFlatsat + " run " + std::string(FLATSAT_SCENARIO_DIR) +
                           "/default.yaml -q --no-plots --out " + run +
                           " --set mode=paced --set duration_orbits=null --set duration_s=25",
                       run + ".log");
  REQUIRE(test::waitForText(fs::path(run) / "logs" / "dynamics_server.log", "every component ready", 120, rig));
  const std::string port = std::to_string(18000 + domain);  // domains are exclusive per test process
  test::Background web(test::kFlatsat + " web --seconds 90 --port " + port, run + "-web.log");
  REQUIRE(test::waitForText(run + "-web.log", "flatsat web: http://127.0.0.1:" + port, 30, web));
  const std::string url = "http://127.0.0.1:" + port + "/";

  // The page fills its table from /state twice a second; discovery of every component's
  // health may take a few seconds after the tool joins.
  const std::set<std::string> components = {"dynamics_server", "magnetometer", "sun_sensor", "gyro", "wheel_tach",
                                            "estimator", "attitude_controller", "unloading_controller", "recorder"};
  std::set<std::string> shown;
  std::string dom;
  int truth_samples = 0;
  for (int attempt = 0; attempt < 10 && (shown != components || truth_samples < 2); ++attempt) {
    dom = test::runCommand(chromium(run + "/chromium", "--dump-dom " + url)).output;
    shown.clear();
    const std::regex row(R"re(<tr data-component="([a-z_]+)"><td>[a-z_]+</td><td class="state">RUNNING)re");
    for (auto it = std::sregex_iterator(dom.begin(), dom.end(), row); it != std::sregex_iterator(); ++it) {
      shown.insert((*it)[1]);
    }
    std::smatch status;
    if (std::regex_search(dom, status, std::regex(R"((\d+) truth samples)"))) truth_samples = std::stoi(status[1]);
    if (shown != components) std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  INFO(dom);
  CHECK(shown == components);
  CHECK(truth_samples >= 2);  // the plots have live data
  CHECK(dom.find("<title>flatsat live</title>") != std::string::npos);

  const std::string png = run + "/web.png";
  test::runCommand(chromium(run + "/chromium", "--window-size=1200,900 --screenshot=" + png + " " + url));
  REQUIRE(fs::exists(png));
  CHECK(fs::file_size(png) > 10'000);  // a rendered page, not a blank one
  CHECK(rig.wait(120) == 0);
  fs::remove_all(run);
  fs::remove(run + ".log");
  fs::remove(run + "-web.log");
}
