// SPDX-License-Identifier: Apache-2.0
#include "tools/InfoCommand.hpp"

#include <iostream>
#include <memory>

#include "analysis/McapExport.hpp"
#include "analysis/RecordingInfo.hpp"
#include "tools/ReportErrors.hpp"

namespace flatsat::tools {

CLI::App* addInfoCommand(CLI::App& app, int& exit_code) {
  struct Options {
    std::string recording;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("info", "what a recording holds: scenario, digest, durations, size, and per topic "
                                         "its type, samples and rate");
  cmd->add_option("recording", options->recording, "recording.sqlite of a run, or an MCAP file of flatsat export --mcap")
      ->required();
  cmd->add_flag("--json", options->json, "one JSON object instead of the table");
  cmd->footer(
      "The digest is the run's recording_sha256 (summary.json): every sample but the\n"
      "wall-clock ones, computed again from the file; it exits 1 when it differs from\n"
      "the one the recorder kept as it stored the samples (they changed since). Rates are samples over the whole run's simulated span; the wall\n"
      "duration spans the recorded health samples' clocks. Of an MCAP file it reads the\n"
      "summary and the \"flatsat\" metadata, and lists the derived channels too.");
  cmd->callback([options, &exit_code] {
    runReportingErrors(exit_code, [&] {
      const auto info = analysis::isMcap(options->recording) ? analysis::describeMcap(options->recording)
                                                             : analysis::describeRecording(options->recording);
      if (options->json) {
        std::cout << analysis::toJson(info).dump(2) << "\n";
      } else {
        std::cout << analysis::infoTable(info);
      }
      return info.changedSinceRecorded() ? 1 : 0;
    });
  });
  return cmd;
}

}  // namespace flatsat::tools
