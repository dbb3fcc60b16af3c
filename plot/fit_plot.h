// PNG of fit versus data for birotor-identify --plot: one panel per FitPlot of
// the identification result (measured points, fitted model as a line), drawn
// by the project's gnuplot driver (plot/gnuplot_driver.h): no shell, no
// files beside the PNG.
#pragma once

#include <string>
#include <vector>

#include "identification/identification_result.h"

namespace birotor {

// Title and axis labels of one panel (with units).
struct FitPlotText {
  std::string title;
  std::string x_label;
  std::string y_label;
};
FitPlotText FitPlotLabels(const FitPlot& plot);

// Writes png_path (temporary file + rename) with the panels in a two-column
// grid. False with *error when there is nothing to plot or gnuplot fails.
bool WriteFitPlot(const std::vector<FitPlot>& plots, const std::string& title, const std::string& png_path,
                  std::string* error);

}  // namespace birotor
