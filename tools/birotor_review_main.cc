// birotor-review: one self-contained HTML page (works offline) to look into a
// flight log: what the estimator and the controller did, on one zoomable time
// axis (review/review_page.h); with two logs, both overlaid (A and B). Prints
// each channel's message count (with two logs after "A:" / "B:"), then the
// flight figures and the headline ("flight: ..." and "flight: headline: ..." lines).
#include <spdlog/spdlog.h>

#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "program/logging.h"
#include "program/program_options.h"
#include "review/flight_data.h"
#include "review/review_page.h"
#include "transport/channels.h"
#include "transport/host_clock.h"
#include "transport/log_io.h"
#include "transport/output_file.h"
#include "transport/wire_text.h"

int main(int argc, char** argv) {
  using namespace birotor;
  CLI::App app{
      "birotor-review: a flight log as one self-contained HTML page (forces, status, NIS, inputs, "
      "controller) with zoom and pan on a shared time axis"};
  std::vector<std::string> log_paths;
  std::string output_path;
  std::string prefix = kDefaultChannelPrefix;
  std::string log_level = "info";
  double min_usable_fraction = kDefaultMinUsableLogFraction;
  app.set_version_flag("--version", BIROTOR_VERSION);
  app.option_defaults()->always_capture_default();
  app.add_option("logs", log_paths,
                 "LCM log: a flight (birotor-sim --controller), a replay output or a recording; a second log is "
                 "overlaid on the first (A and B)")
      ->required()
      ->expected(1, 2);
  app.add_option("--output", output_path, "HTML page to write")->required();
  app.add_option("--prefix", prefix, "Channel name prefix");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));
  app.add_option("--min-usable-fraction", min_usable_fraction,
                 "Refuse a log whose readable events are less than this share of its bytes")
      ->check(CLI::Range(0.0, 1.0));
  if (const auto exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-review", log_level);

  std::string error;
  if (!CheckOutputs({output_path}, log_paths, &error)) return ReportError(error);
  const Stopwatch stopwatch;
  std::vector<FlightData> data(log_paths.size());
  std::vector<const FlightData*> logs;
  for (size_t k = 0; k < log_paths.size(); ++k) {
    if (!ReadFlightData(log_paths[k], prefix, min_usable_fraction, &data[k], &error)) return ReportError(error);
    logs.push_back(&data[k]);
  }
  const double read_s = stopwatch.ElapsedS();
  const std::string html = ReviewPageHtml(logs);
  OutputFile output;
  if (!output.Open(output_path, &error) || !output.Write(html) || !output.Commit(&error)) {
    return ReportError(error.empty() ? "writing " + output_path + " failed" : error);
  }
  for (size_t k = 0; k < data.size(); ++k) {
    // With two logs every line names its log: "A: BIROTOR_FORCE 15000", "A: flight: ...".
    const std::string name = data.size() > 1 ? std::string(1, char('A' + k)) + ": " : "";
    for (const auto& [channel, count] : data[k].channels) {
      std::cout << name << PrintableWireText(channel) << " " << count.messages << "\n";
    }
    std::istringstream summary(FlightSummaryText(data[k]));
    for (std::string line; std::getline(summary, line);) std::cout << name << line << "\n";
    spdlog::info("{}: {} events, {:.3f} s", PrintableWireText(log_paths[k]), data[k].events, data[k].duration_s);
  }
  spdlog::info("{} written ({:.2f} MB) in {:.3f} s (read {:.3f} s)", output_path,
               1e-6 * static_cast<double>(html.size()), stopwatch.ElapsedS(), read_s);
  return 0;
}
