// PNG plots of estimated versus true rotor force and of the force error over
// time (thesis figures 5.1 and 5.2), drawn by gnuplot from a data file.
#pragma once

#include <string>
#include <vector>

#include "estimator/samples.h"

namespace birotor {

// Writes png_path (and png_path + ".dat", + ".gp" beside it) with three
// panels: f1 estimated/true, f2 estimated/true, errors f_est - f_true.
// Estimates are paired with truth by utime. False with *error if gnuplot
// fails or nothing could be paired.
bool WriteForcePlot(const std::vector<ForceEstimate>& forces, const std::vector<TruthSample>& truth,
                    const std::string& title, const std::string& png_path, std::string* error);

}  // namespace birotor
