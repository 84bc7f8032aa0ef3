// SPDX-License-Identifier: Apache-2.0
#pragma once
// Where in the user's files a scenario problem is. A scenario is merged from
// its file and the bases it names, and the merged tree's line numbers do not
// say which file they are of: a problem is placed again by its key path, in
// the first file of the chain (the user's own, then its bases) that writes it.
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace flatsat::bus {

/// 1-based "line:col" of `key` ("a.b[2].c") in a YAML file; "" when absent.
std::string placeOf(const std::string& file, const std::string& key);

/// "<reported>[:L:C]: key: reason" placed at the key in the first of `files`
/// (top first) that writes it; with no file writing it, the reported file
/// without a line when there are bases (their lines would mislead), else as
/// it came. Problems of another shape are returned as they are.
std::string placeProblem(const std::string& problem, const std::string& reported,
                         const std::vector<std::string>& files);

/// "file:L:C: path: duplicate key ..." for every key written twice in one
/// mapping of `root` (YAML parsers keep one of them silently).
std::vector<std::string> duplicateKeys(const YAML::Node& root, const std::string& file);

}  // namespace flatsat::bus
