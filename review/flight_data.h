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

#include "model/vehicle_description.h"
#include "samples/flight_figures.h"
#include "samples/rotor_count.h"

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
  void Add(double t, std::initializer_list<double> values) { Add(t, values.begin(), values.size()); }
  void Add(double t, const double* values, size_t count);
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
  // Rotors of the vehicle the log flew (N below): 2 for the birotor's
  // channels (FORCE, TRUTH, MOTOR_COMMAND), else the count of the first
  // counted message (FORCE_N, TRUTH_N, MOTOR_COMMAND_N; docs/interface.md).
  int rotor_count = kBirotorRotors;
  // Messages of another rotor count than rotor_count (a second vehicle in
  // the log): dropped whole and counted here and as decode errors.
  int64_t count_mismatches = 0;
  // FORCE or FORCE_N: force_n[N], force_std_n[N], thrust_scale[N], status
  // (the vehicle-wide bits), rotor_fault_bits (bit i: rotor i + 1; a
  // birotor FORCE's ROTOR1/2_FAULT bits are moved here, as ToCountedMessage does).
  Table force;
  // TRUTH or TRUTH_N: force_n[N], thrust_scale[N], x_m, z_m, phi_rad.
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
  // MOTOR_COMMAND or MOTOR_COMMAND_N: omega_cmd_rad_s[N], mode, status.
  Table motor_command;
  // CONTROLLER_STATUS: fallbacks, descents, saturated, commands, mode.
  Table controller_status;
  // SETPOINT: x_m, z_m (where the vehicle was meant to be).
  Table setpoint;

  // Lays force, truth and motor_command out for n rotors, labels included
  // (while they hold no row).
  void SetRotorCount(int n);
  // Column indices of the per-rotor tables (rotor 0-based, N = rotor_count).
  int ForceColumn(int rotor) const { return rotor; }
  int ForceSigmaColumn(int rotor) const { return rotor_count + rotor; }
  int ForceScaleColumn(int rotor) const { return 2 * rotor_count + rotor; }
  int ForceStatusColumn() const { return 3 * rotor_count; }
  int ForceFaultColumn() const { return 3 * rotor_count + 1; }
  int TruthForceColumn(int rotor) const { return rotor; }
  int TruthScaleColumn(int rotor) const { return rotor_count + rotor; }
  int TruthXColumn() const { return 2 * rotor_count; }
  int TruthZColumn() const { return 2 * rotor_count + 1; }
  int TruthPhiColumn() const { return 2 * rotor_count + 2; }
  int CommandColumn(int rotor) const { return rotor; }
  int CommandModeColumn() const { return rotor_count; }
  int CommandStatusColumn() const { return rotor_count + 1; }
};

// One FORCE flag as the review shows it: a bit of a column of the force
// table, with its word ("VALID", "ROTOR3_FAULT") and whether it is an alarm.
struct ForceFlag {
  int column = 0;
  int32_t bit = 0;
  std::string word;
  bool alarm = false;
};
// Every FORCE flag in the order of force_estimate_t's bits, the rotor-fault
// bits expanded to one flag per rotor (ROTOR1_FAULT .. ROTOR<N>_FAULT).
std::vector<ForceFlag> ForceFlags(const FlightData& data);

// The input channels whose rates and gaps are shown, in input_t_s order.
inline constexpr int kReviewRateInputs = 4;

// Reads path with channel prefix (e.g. "BIROTOR_"). False with a one-line
// *error when the file cannot be read, is not a usable log (less than
// min_usable_fraction of its bytes in readable events) or holds no message.
bool ReadFlightData(const std::string& path, const std::string& prefix, double min_usable_fraction, FlightData* data,
                    std::string* error);

}  // namespace birotor
