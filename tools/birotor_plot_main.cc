// birotor-plot: PNG of estimated versus true rotor force and the error over
// time from a log holding FORCE and TRUTH (the output of birotor-replay).
#include <cstdio>
#include <string>

#include "evaluation/eval_runner.h"
#include "plot/force_plot.h"
#include "transport/logging.h"
#include "transport/program_options.h"

int main(int argc, char** argv) {
  using namespace birotor;
  CLI::App app{"birotor-plot: estimated vs true rotor force (thesis figures 5.1, 5.2)"};
  CommonOptions common;
  AddCommonOptions(app, &common);
  std::string log_path, png_path, title;
  app.add_option("--log", log_path, "LCM log with FORCE and TRUTH (birotor-replay output)")->required();
  app.add_option("--png", png_path, "PNG file to write")->required();
  app.add_option("--title", title, "Plot title (default: the log name)");
  if (const auto exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-plot", common.log_level);

  const ChannelNames channels = MakeChannelNames(common.prefix);
  ForceTruthCollector collector(channels);
  LogReader reader;
  std::string error;
  if (!reader.Open(log_path, &error)) {
    std::fprintf(stderr, "birotor-plot: error: %s\n", error.c_str());
    return 1;
  }
  LogEvent event;
  while (reader.Next(&event)) {
    collector.Publish(event.channel, event.timestamp_us, event.data.data(), event.data.size());
  }
  if (!WriteForcePlot(collector.forces, collector.truth, title.empty() ? log_path : title, png_path, &error)) {
    std::fprintf(stderr, "birotor-plot: error: %s\n", error.c_str());
    return 1;
  }
  std::printf("%s: %zu estimates, %zu truth samples\n", png_path.c_str(), collector.forces.size(),
              collector.truth.size());
  return 0;
}
