// SPDX-License-Identifier: Apache-2.0
// docs/scenario.md documents every key the shipped scenarios use: each key path
// of deploy/scenarios/*.yaml must appear in backticks in the document, so the
// schema cannot fall behind the scenarios. Keys every component
// shares (rate_divider, role, faults, ...) are documented once as
// components.<name>.key.
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>
#include <yaml-cpp/yaml.h>

namespace {

namespace fs = std::filesystem;

/// Every key path under `node`: mappings give "a.b", a list of mappings gives
/// "a[].b" (one path per field, whatever the element); scalars and lists of
/// scalars or lists end a path.
void collectKeys(const YAML::Node& node, const std::string& path, std::set<std::string>& keys) {
  if (node.IsMap()) {
    const bool element = path.size() >= 2 && path.compare(path.size() - 2, 2, "[]") == 0;
    if (!path.empty() && !element) keys.insert(path);
    for (const auto& entry : node) {
      const auto key = entry.first.as<std::string>();
      collectKeys(entry.second, path.empty() ? key : path + "." + key, keys);
    }
  } else if (node.IsSequence() && node.size() > 0 && node[0].IsMap()) {
    keys.insert(path);
    for (const auto& element : node) collectKeys(element, path + "[]", keys);
  } else {
    keys.insert(path);
  }
}

/// "components.gyro.faults[].kind" -> "components.<name>.faults[].kind": the form
/// the document uses for keys every component (or every sensor) shares.
std::string sharedForm(const std::string& key) {
  const std::string prefix = "components.";
  if (key.rfind(prefix, 0) != 0) return key;
  const auto dot = key.find('.', prefix.size());
  if (dot == std::string::npos) return key;
  return prefix + "<name>" + key.substr(dot);
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("Scenario schema: docs/scenario.md documents every key of the shipped scenarios", "[bus][schema]") {
  const fs::path source(FLATSAT_SOURCE_DIR);
  const std::string doc = readFile(source / "docs" / "scenario.md");
  REQUIRE_FALSE(doc.empty());

  std::set<std::string> keys;
  int files = 0;
  for (const auto& entry : fs::directory_iterator(source / "deploy" / "scenarios")) {
    if (entry.path().extension() != ".yaml") continue;
    ++files;
    collectKeys(YAML::LoadFile(entry.path().string()), "", keys);
  }
  REQUIRE(files >= 1);
  // The scenarios' own names for things every reader knows (sanity of the walk).
  REQUIRE(keys.count("orbit.altitude_m") == 1);
  REQUIRE(keys.count("spacecraft.panels[].area_m2") == 1);

  // Appended, not "`" + key: GCC 12 warns (-Wrestrict) on that sum once inlined.
  const auto quoted = [](const std::string& key) { return std::string(1, '`').append(key).append(1, '`'); };
  std::set<std::string> missing;
  for (const auto& key : keys) {
    const bool documented = doc.find(quoted(key)) != std::string::npos ||
                            doc.find(quoted(sharedForm(key))) != std::string::npos;
    if (!documented) missing.insert(key);
  }
  std::string list;
  for (const auto& key : missing) list += "  " + key + "\n";
  INFO(keys.size() << " key paths in " << files << " scenarios; missing from docs/scenario.md:\n"
                   << list);
  CHECK(missing.empty());
}
