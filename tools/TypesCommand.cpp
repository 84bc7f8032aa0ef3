// SPDX-License-Identifier: Apache-2.0
#include "tools/TypesCommand.hpp"

#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "analysis/McapSchemas.hpp"
#include "tools/ToolBus.hpp"

namespace flatsat::tools {

namespace {

/// Each registry type ("flatsat::msg::TruthState") with the topics that carry it.
std::map<std::string, std::vector<std::string>> registryTypes() {
  std::map<std::string, std::vector<std::string>> types;
  bus::forEachTopic([&](const auto& def) {
    types[typename std::remove_cvref_t<decltype(def)>::PubSubType().getName()].push_back(std::string(def.name));
  });
  return types;
}

/// The full type name `what` names: itself, its last part ("TruthState") or
/// a topic of that type ("truth", "flatsat/truth"); "" when none.
std::string typeNamed(const std::string& what) {
  for (const auto& [type, topics] : registryTypes()) {
    const auto last = type.substr(type.rfind(':') + 1);
    if (what == type || what == last) return type;
    for (const auto& topic : topics) {
      if (what == topic || what == shortTopicName(topic)) return type;
    }
  }
  return "";
}

int showTypes(const std::string& what) {
  const auto types = registryTypes();
  if (what.empty()) {
    std::printf("%-34s %s\n", "TYPE", "TOPICS");
    for (const auto& [type, topics] : types) {
      std::string joined;
      for (const auto& t : topics) joined += (joined.empty() ? "" : ", ") + t;
      std::printf("%-34s %s\n", type.c_str(), joined.c_str());
    }
    return 0;
  }
  const auto type = typeNamed(what);
  if (type.empty()) {
    std::string known;
    for (const auto& [name, topics] : types) known += (known.empty() ? "" : ", ") + name.substr(name.rfind(':') + 1);
    std::cerr << "error: no type or topic '" << what << "'; the types: " << known << "\n";
    return 2;
  }
  std::cout << "// " << type << "\n" << analysis::omgIdlSchema(type);
  return 0;
}

}  // namespace

CLI::App* addTypesCommand(CLI::App& app, int& exit_code) {
  auto what = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("types", "the topic types, or one type's OMG IDL definition");
  cmd->add_option("type", *what, "a type (TruthState, flatsat::msg::TruthState) or a topic (truth, flatsat/truth)");
  cmd->footer("The IDL is self-contained (includes inlined): the schema the MCAP export and\n"
              "`flatsat foxglove` send, which Foxglove's OMG IDL reader takes.");
  cmd->callback([what, &exit_code] { exit_code = showTypes(*what); });
  return cmd;
}

}  // namespace flatsat::tools
