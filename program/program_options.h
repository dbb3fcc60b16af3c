// Command-line options every program shares (--lcm-url, --prefix,
// --log-level, --version), one way to parse with CLI11 (help to stdout and
// exit 0, a usage error as one line on stderr and exit 2), and the one error
// format of every program: "<program>: error: <message>" on one line, exit 1
// for bad files or data, 2 for bad usage.
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

// Exit statuses shared by every program.
constexpr int kExitFailure = 1;  // a bad file, bad data, a failed write, no input
constexpr int kExitUsage = 2;    // a bad command line

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
// An unknown option is named even when a required option is missing too.
std::optional<int> ParseCommandLine(CLI::App& app, int argc, const char* const* argv);
std::optional<int> ParseCommandLine(CLI::App& app, int argc, const char* const* argv, std::ostream& out,
                                    std::ostream& err);

// Writes "<program>: error: <message>" as one line to err (line breaks in
// message become spaces) and returns exit_status, so a program ends with
// `return ReportError(...)`. The program is the name the process was
// started with (basename of argv[0]) unless given.
int ReportError(const std::string& message, int exit_status = kExitFailure);
int ReportError(std::ostream& err, const std::string& program, const std::string& message,
                int exit_status = kExitFailure);

}  // namespace birotor
