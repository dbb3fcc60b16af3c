// Tests of transport/program_options.h.
#include "program/program_options.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <vector>

namespace birotor {
namespace {

// Runs ParseCommandLine on a program "prog" with the common options and one
// of its own.
struct ParsedRun {
  explicit ParsedRun(std::vector<const char*> args) {
    args.insert(args.begin(), "/usr/bin/prog");
    CLI::App app("A test program", "prog");
    AddCommonOptions(app, &options);
    app.add_option("--rate-hz", rate_hz, "Publish rate [Hz]");
    result = ParseCommandLine(app, static_cast<int>(args.size()), args.data(), out, err);
  }
  CommonOptions options;
  double rate_hz = 1000.0;
  std::ostringstream out, err;
  std::optional<int> result;
};

TEST(ParseCommandLineTest, ValidOptionsContinue) {
  ParsedRun run({"--lcm-url", "memq://", "--prefix=V2_", "--log-level", "debug", "--rate-hz", "250"});
  EXPECT_EQ(run.result, std::nullopt);
  EXPECT_EQ(run.options.lcm_url, "memq://");
  EXPECT_EQ(run.options.prefix, "V2_");
  EXPECT_EQ(run.options.log_level, "debug");
  EXPECT_EQ(run.rate_hz, 250.0);
  EXPECT_EQ(run.err.str(), "");
}

TEST(ParseCommandLineTest, DefaultsWithoutArguments) {
  ParsedRun run({});
  EXPECT_EQ(run.result, std::nullopt);
  EXPECT_EQ(run.options.lcm_url, "udpm://239.255.76.67:7667?ttl=0");
  EXPECT_EQ(run.options.prefix, "BIROTOR_");
  EXPECT_EQ(run.options.log_level, "info");
}

TEST(ParseCommandLineTest, UnknownOptionIsOneLineAndExitTwo) {
  ParsedRun run({"--bogus"});
  EXPECT_EQ(run.result, 2);
  const std::string err = run.err.str();
  EXPECT_EQ(err.rfind("prog: error: ", 0), 0u) << err;
  EXPECT_NE(err.find("--bogus"), std::string::npos) << err;
  EXPECT_NE(err.find("(see --help)\n"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_EQ(run.out.str(), "");
}

TEST(ParseCommandLineTest, BadLogLevelIsAnError) {
  ParsedRun run({"--log-level", "loud"});
  EXPECT_EQ(run.result, 2);
  const std::string err = run.err.str();
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_NE(err.find("loud"), std::string::npos) << err;
}

TEST(ParseCommandLineTest, HelpPrintsOptionsWithDefaultsAndExitsZero) {
  ParsedRun run({"--help"});
  EXPECT_EQ(run.result, 0);
  const std::string help = run.out.str();
  EXPECT_NE(help.find("--lcm-url"), std::string::npos) << help;
  EXPECT_NE(help.find("udpm://239.255.76.67:7667?ttl=0"), std::string::npos) << help;
  EXPECT_NE(help.find("BIROTOR_"), std::string::npos) << help;
  EXPECT_NE(help.find("--rate-hz"), std::string::npos) << help;
  EXPECT_NE(help.find("1000"), std::string::npos) << help;
  EXPECT_EQ(run.err.str(), "");
}

TEST(ParseCommandLineTest, VersionPrintsProgramAndVersion) {
  ParsedRun run({"--version"});
  EXPECT_EQ(run.result, 0);
  EXPECT_EQ(run.out.str(), std::string("prog ") + BIROTOR_VERSION + "\n");
}

TEST(ParseCommandLineTest, UnknownOptionIsNamedEvenWhenARequiredOneIsMissing) {
  // Issue 14: `birotor-sim --bogus-option` said "--scenario is required".
  std::vector<const char*> args = {"/usr/bin/prog", "--bogus-option"};
  CLI::App app("A test program", "prog");
  std::string scenario;
  app.add_option("--scenario", scenario, "Scenario")->required();
  std::ostringstream out, err;
  EXPECT_EQ(ParseCommandLine(app, static_cast<int>(args.size()), args.data(), out, err), kExitUsage);
  EXPECT_EQ(err.str(), "prog: error: unknown argument '--bogus-option'; also: --scenario is required (see --help)\n");
}

TEST(ReportErrorTest, OneLineInTheCommonFormatWithTheGivenStatus) {
  std::ostringstream err;
  EXPECT_EQ(ReportError(err, "birotor-x", "bad file\nsecond line"), kExitFailure);
  EXPECT_EQ(err.str(), "birotor-x: error: bad file second line\n");
  std::ostringstream usage;
  EXPECT_EQ(ReportError(usage, "birotor-x", "--rate-hz: out of range", kExitUsage), 2);
}

}  // namespace
}  // namespace birotor
