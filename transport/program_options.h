// Command-line options every program shares (--lcm-url, --prefix,
// --log-level, --version) and one way to parse with CLI11: help to stdout and
// exit 0, an error as one line on stderr and exit 2.
#pragma once

#include <CLI/CLI.hpp>
#include <iosfwd>
#include <optional>
#include <string>

#include "transport/channels.h"
#include "transport/lcm_session.h"

#ifndef BIROTOR_VERSION
#define BIROTOR_VERSION "unknown"
#endif

namespace birotor {

struct CommonOptions {
  // LCM URL to publish and subscribe on.
  std::string lcm_url = kDefaultLcmUrl;
  // Channel name prefix (several vehicles on one LCM network).
  std::string prefix = kDefaultChannelPrefix;
  // spdlog level: trace, debug, info, warn, error or off.
  std::string log_level = "info";
};

// Adds --lcm-url, --prefix, --log-level and --version to app, and makes
// --help show every option's default. Call it right after constructing the
// app, before the program's own options, so those show defaults too.
void AddCommonOptions(CLI::App& app, CommonOptions* options);

// Parses the command line. Returns the exit code when the program should stop
// (0 after --help or --version, 2 after a usage error, reported as one line
// "<program>: error: <message> (see --help)"), std::nullopt to continue.
std::optional<int> ParseCommandLine(CLI::App& app, int argc, const char* const* argv);
std::optional<int> ParseCommandLine(CLI::App& app, int argc, const char* const* argv, std::ostream& out,
                                    std::ostream& err);

}  // namespace birotor
