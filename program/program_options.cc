// Shared CLI11 options and parsing.
#include "program/program_options.h"

#include <errno.h>  // program_invocation_short_name (glibc)

#include <iostream>

namespace birotor {
namespace {

// "tools/replay" -> "replay", for messages about the program.
std::string ProgramName(const CLI::App& app) {
  const std::string& name = app.get_name();
  const size_t slash = name.find_last_of('/');
  return slash == std::string::npos ? name : name.substr(slash + 1);
}

}  // namespace

void AddCommonOptions(CLI::App& app, CommonOptions* options) {
  app.option_defaults()->always_capture_default();
  app.add_option("--lcm-url", options->lcm_url, "LCM URL (memq:// for tests, file:// for logs)");
  app.add_option("--prefix", options->prefix,
                 "Channel name prefix (at most " + std::to_string(kMaxChannelPrefixBytes) +
                     " printable ASCII bytes: LCM channel names are at most 63)")
      ->check(CLI::Validator(ChannelPrefixProblem, "PREFIX", "ChannelPrefix"));
  app.add_option("--log-level", options->log_level, "Log level")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));
  app.set_version_flag("--version", [&app] { return ProgramName(app) + " " + BIROTOR_VERSION; });
}

std::optional<int> ParseCommandLine(CLI::App& app, int argc, const char* const* argv) {
  return ParseCommandLine(app, argc, argv, std::cout, std::cerr);
}

std::optional<int> ParseCommandLine(CLI::App& app, int argc, const char* const* argv, std::ostream& out,
                                    std::ostream& err) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
      return app.exit(e, out, err);  // --help, --help-all, --version
    }
    std::string message = e.what();
    // CLI11 checks required options before it looks at unknown arguments:
    // name the unknown one, which is usually the cause (a misspelt option).
    const std::vector<std::string> extras = app.remaining();
    if (dynamic_cast<const CLI::RequiredError*>(&e) != nullptr && !extras.empty()) {
      message =
          "unknown argument '" + extras.front() + "'" + (extras.size() > 1 ? " (and more)" : "") + "; also: " + message;
    }
    return ReportError(err, ProgramName(app), message + " (see --help)", kExitUsage);
  }
  return std::nullopt;
}

int ReportError(const std::string& message, int exit_status) {
  return ReportError(std::cerr, program_invocation_short_name, message, exit_status);
}

int ReportError(std::ostream& err, const std::string& program, const std::string& message, int exit_status) {
  std::string line = message;
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';  // one line, whatever the message holds
  }
  err << program << ": error: " << line << std::endl;
  return exit_status;
}

}  // namespace birotor
