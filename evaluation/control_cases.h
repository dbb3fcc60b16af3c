// The closed-loop comparison cases of birotor-eval --control (issue 25): a
// scenario file plus scenario overrides (the same syntax as --set), so a
// mismatch case is the reference scenario with one thing changed on the
// vehicle or its sensors and nothing changed in the controller's or the
// estimator's model.
#pragma once

#include <string>
#include <vector>

#include "controller/controller_params.h"

namespace birotor {

struct ControlCase {
  std::string name;                    // table label and plot file name
  std::string scenario;                // scenarios/<scenario>.yaml
  std::vector<std::string> overrides;  // section.key=value, applied in order
  std::string what;                    // one line for the table and the docs
  // > 0: the case flies with these setpoint shaping limits (setpoint
  // max_speed_m_s, max_accel_m_s2) instead of the controller file's; a case
  // that tests the controllers beyond what the shipped shaping lets through.
  double reference_max_speed_m_s = 0;
  double reference_max_accel_m_s2 = 0;
};

// The controller configuration case c flies: base with its shaping limits.
ControllerConfig ControllerForCase(const ControlCase& c, ControllerConfig base);

// Every case, in table order: the kept ones (hover, gentle, aggressive,
// thrust_loss), then the issue 25 table.
const std::vector<ControlCase>& ControlCases();
// The case of that name, or nullptr.
const ControlCase* FindControlCase(const std::string& name);

}  // namespace birotor
