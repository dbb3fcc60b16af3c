// One LCM log read for the flight review (birotor-review): every message of
// the channels the page shows decoded into columns over time [s from the
// first message], and every channel counted (also those it cannot decode,
// such as a SETPOINT of a newer build). Nothing is decimated here: counts,
// first rises, rates and gaps are computed on all samples.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "samples/flight_figures.h"

namespace birotor {

// Columns sharing one time axis, e.g. FORCE's force_n[0], force_n[1], ...
struct Table {
  std::vector<std::string> labels;           // one per column, with the unit
  std::vector<double> t_s;                   // time of each row [s from the log's first message]
  std::vector<std::vector<double>> columns;  // columns[c][row]

  Table() = default;
  explicit Table(std::vector<std::string> column_labels) : labels(std::move(column_labels)), columns(labels.size()) {}
  size_t rows() const { return t_s.size(); }
  // Appends one row; values must have labels.size() entries.
  void Add(double t, std::initializer_list<double> values);
};

// Per channel: messages in the log, decode failures, first and last time.
struct ChannelCount {
  int64_t messages = 0;
  int64_t decode_errors = 0;
  double first_s = 0.0;
  double last_s = 0.0;
};

// The estimator's inputs in ESTIMATOR_STATUS order, then its accelerometer.
inline constexpr int kReviewInputs = 5;
extern const char* const kReviewInputNames[kReviewInputs];  // "STRAIN", ..., "IMU accel_z"

struct FlightData {
  FlightData();  // every table with its labels, no rows

  std::string path;
  int64_t events = 0;
  int64_t t0_utime = 0;  // utime of the first decoded message; t = 0 there
  double duration_s = 0.0;
  std::map<std::string, ChannelCount> channels;  // every channel of the log by name
  // FORCE: force_n[2], force_std_n[2], thrust_scale[2], status.
  Table force;
  // TRUTH: force_n[2], thrust_scale[2], x_m, z_m, phi_rad.
  Table truth;
  // The flight's figures (RMS, max tilt, fallbacks) by the one definition
  // (samples/flight_figures.h), fed SETPOINT, TRUTH and MOTOR_COMMAND in log order.
  FlightFigures figures;
  // ESTIMATOR_STATUS: per input (kReviewInputs) NIS mean, fused, rejected
  // (gate + invalid), received; then resets.
  Table status;
  // Times of the input messages (STRAIN, MOTOR, IMU, POSE) for rates and gaps.
  std::vector<double> input_t_s[4];
  // POSE: x_m, z_m, phi_rad.
  Table pose;
  // IMU: gyro_y_rad_s (body pitch rate).
  Table imu;
  // MOTOR_COMMAND: omega_cmd_rad_s[2], mode, status.
  Table motor_command;
  // CONTROLLER_STATUS: fallbacks, descents, saturated, commands, mode.
  Table controller_status;
  // SETPOINT: x_m, z_m (where the vehicle was meant to be).
  Table setpoint;
};

// The input channels whose rates and gaps are shown, in input_t_s order.
inline constexpr int kReviewRateInputs = 4;

// Reads path with channel prefix (e.g. "BIROTOR_"). False with a one-line
// *error when the file cannot be read, is not a usable log (less than
// min_usable_fraction of its bytes in readable events) or holds no message.
bool ReadFlightData(const std::string& path, const std::string& prefix, double min_usable_fraction, FlightData* data,
                    std::string* error);

}  // namespace birotor
