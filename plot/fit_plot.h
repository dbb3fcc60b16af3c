// PNG of fit versus data for birotor-identify --plot: one panel per FitPlot of
// the identification result (measured points, fitted model as a line), drawn
// by gnuplot (Debian gnuplot-nox) from a temporary data file.
#pragma once

#include <string>
#include <vector>

#include "identification/identification_result.h"

namespace birotor {

// Writes png_path with the panels in a two-column grid. The data file and
// the gnuplot script are temporary files in $TMPDIR (or /tmp), removed
// afterwards. False with *error when there is nothing to plot, gnuplot cannot
// be run or fails.
bool WriteFitPlot(const std::vector<FitPlot>& plots, const std::string& title, const std::string& png_path,
                  std::string* error);

}  // namespace birotor
