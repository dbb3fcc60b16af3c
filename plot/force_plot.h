// The force plot an engineer reads at a glance (thesis figures 5.1 and 5.2,
// extended): per rotor the estimated force with its 1-sigma band (and the true
// force when TRUTH exists), the error against truth with the 1-sigma band, the
// thrust efficiency with the fault threshold, and a strip of every status bit
// over time. The first rise of each fault, stale and reset bit is marked by a
// vertical line with its time; y-ranges follow the data, and a transient that
// leaves the range is noted with its peak.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "estimator/estimator_config.h"
#include "samples/samples.h"

namespace birotor {

// A vertical line across every panel, labelled in the top one.
struct PlotMarker {
  int64_t utime = 0;  // vehicle clock [us]
  std::string label;  // e.g. "thrust step rotor 2"; the time is appended
};

// A horizontal line on the thrust-efficiency panel.
struct ThresholdLine {
  double value = 0;   // [1]
  std::string label;  // e.g. "rotor fault below 0.85"
};

// The estimator's thrust-efficiency thresholds (its fault semantics, from
// ekf) as lines: the one place that knows what the status bits mean in mu.
std::vector<ThresholdLine> ThrustScaleLines(const EkfOptions& ekf);

// The labels of lines joined with ", " (the monitor's words).
std::string ThresholdWords(const std::vector<ThresholdLine>& lines);

// The step of true thrust efficiency that birotor-eval finds (EvalResult's
// step_rotor 1 or 2, step_time_s on the vehicle clock [s]).
PlotMarker ThrustStepMarker(int rotor, double step_time_s);

// The default title: what the plot shows and the log's file name.
std::string ForcePlotTitle(const std::string& log_path);

struct ForcePlotOptions {
  std::string title;
  // The estimator's thresholds on the thrust-efficiency panel.
  std::vector<ThresholdLine> scale_lines = ThrustScaleLines(EkfOptions{});
  // Extra vertical lines, e.g. the thrust step found in truth.
  std::vector<PlotMarker> markers;
  // Share of a panel's samples that may fall outside its y-range at each end:
  // the range follows the bulk of the data, and a short transient (the
  // thrust-loss spike) runs off the edge with a note giving its peak [1].
  double clip_fraction = 0.002;
  int width_px = 1200;
  int height_px = 1300;
};

// The gnuplot script of the plot, data inline (what WriteForcePlot runs; the
// tests read its labels). forces must not be empty.
std::string ForcePlotScript(const std::vector<ForceEstimate>& forces, const std::vector<TruthSample>& truth,
                            const ForcePlotOptions& options);

// Writes png_path (temporary file + rename, nothing beside it). truth may be
// empty (a real vehicle): then no true lines and no error panel. Estimates are
// paired with truth by utime. False with *error if there is no estimate or
// gnuplot fails.
bool WriteForcePlot(const std::vector<ForceEstimate>& forces, const std::vector<TruthSample>& truth,
                    const ForcePlotOptions& options, const std::string& png_path, std::string* error);

}  // namespace birotor
