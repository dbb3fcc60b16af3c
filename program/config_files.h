// Where every program finds its default parameter and scenario files, so an
// installed program runs from any directory without the source tree. Search
// order, first existing file wins:
//   1. $XDG_CONFIG_HOME/birotor/<name>  (default $HOME/.config/birotor): the user's own
//   2. /etc/birotor/<name>: the site's own files
//   3. <dir of the executable>/../share/birotor/config/<name>: the shipped
//      reference files (the install prefix; in the build tree a link to the
//      source tree's config/ made at configure time)
#pragma once

#include <string>
#include <vector>

namespace birotor {

// The folders searched, in order (see above).
std::vector<std::string> ConfigSearchDirs();

// The first existing <dir>/<name> of ConfigSearchDirs(), e.g. name
// "estimator.yaml" or "scenarios/hover.yaml". When none exists, the shipped
// path (the last folder), so that the error names the expected place.
std::string FindConfigFile(const std::string& name);

// "first of A, B, C" for --help texts.
std::string ConfigSearchText(const std::string& name);

// A scenario argument: a path as given, or a bare name such as "hover" (no
// '/' and no ".yaml") looked up as scenarios/<name>.yaml.
std::string ResolveScenario(const std::string& name_or_path);

// Names of the scenarios (scenarios/<name>.yaml) in every folder of
// ConfigSearchDirs(), sorted, each once.
std::vector<std::string> ScenarioNames();

// ResolveScenario, and false with a one-line *error when the file does not
// exist; for a bare name the error lists ScenarioNames() (issue 24).
bool FindScenario(const std::string& name_or_path, std::string* path, std::string* error);

}  // namespace birotor
