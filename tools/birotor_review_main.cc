// birotor-review: one self-contained HTML page (works offline) to look into a
// flight log: what the estimator and the controller did, on one zoomable time
// axis (review/review_page.h). Prints each channel's message count, then the
// flight figures ("flight: ..." lines).
#include <spdlog/spdlog.h>

#include <iostream>
#include <string>

#include "program/logging.h"
#include "program/program_options.h"
#include "review/flight_data.h"
#include "review/review_page.h"
#include "transport/channels.h"
#include "transport/host_clock.h"
#include "transport/log_io.h"
#include "transport/output_file.h"

int main(int argc, char** argv) {
  using namespace birotor;
  CLI::App app{
      "birotor-review: a flight log as one self-contained HTML page (forces, status, NIS, inputs, "
      "controller) with zoom and pan on a shared time axis"};
  std::string log_path, output_path;
  std::string prefix = kDefaultChannelPrefix;
  std::string log_level = "info";
  double min_usable_fraction = kDefaultMinUsableLogFraction;
  app.set_version_flag("--version", BIROTOR_VERSION);
  app.option_defaults()->always_capture_default();
  app.add_option("log", log_path, "LCM log: a flight (birotor-sim --controller), a replay output or a recording")
      ->required();
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
  if (!CheckOutputs({output_path}, {log_path}, &error)) return ReportError(error);
  const Stopwatch stopwatch;
  FlightData data;
  if (!ReadFlightData(log_path, prefix, min_usable_fraction, &data, &error)) return ReportError(error);
  const double read_s = stopwatch.ElapsedS();
  const std::string html = ReviewPageHtml(data);
  OutputFile output;
  if (!output.Open(output_path, &error) || !output.Write(html) || !output.Commit(&error)) {
    return ReportError(error.empty() ? "writing " + output_path + " failed" : error);
  }
  for (const auto& [channel, count] : data.channels) {
    std::cout << channel << " " << count.messages << "\n";
  }
  std::cout << FlightSummaryText(data);
  spdlog::info("{}: {} events, {:.3f} s; {} written ({:.2f} MB) in {:.3f} s (read {:.3f} s)", log_path, data.events,
               data.duration_s, output_path, 1e-6 * static_cast<double>(html.size()), stopwatch.ElapsedS(), read_s);
  return 0;
}
