#include "review/flight_data.h"

#include <fmt/format.h>

#include <algorithm>
#include <string_view>

#include "birotor/controller_status_t.hpp"
#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_n_t.hpp"
#include "birotor/force_estimate_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/motor_command_n_t.hpp"
#include "birotor/motor_command_t.hpp"
#include "birotor/pose_t.hpp"
#include "birotor/setpoint_t.hpp"
#include "birotor/truth_n_t.hpp"
#include "birotor/truth_t.hpp"
#include "plot/status_words.h"
#include "transport/channels.h"
#include "transport/counted_messages.h"
#include "transport/lcm_codec.h"
#include "transport/log_io.h"
#include "transport/message_conversion.h"

namespace birotor {

const char* const kReviewInputNames[kReviewInputs] = {"STRAIN", "MOTOR", "IMU", "POSE", "IMU accel_z"};

void Table::Add(double t, const double* values, size_t count) {
  t_s.push_back(t);
  for (size_t c = 0; c < count; ++c) columns[c].push_back(values[c]);
}

namespace {

// "force 1 [N]", "force 2 [N]", ...: one label per rotor.
void AddRotorLabels(const char* name, const char* unit, int n, std::vector<std::string>* labels) {
  for (int i = 0; i < n; ++i) labels->push_back(fmt::format("{} {} [{}]", name, i + 1, unit));
}

}  // namespace

void FlightData::SetRotorCount(int n) {
  rotor_count = n;
  std::vector<std::string> labels;
  AddRotorLabels("force", "N", n, &labels);
  AddRotorLabels("sigma", "N", n, &labels);
  AddRotorLabels("thrust scale", "1", n, &labels);
  labels.insert(labels.end(), {"status [bits]", "rotor faults [bits]"});
  force = Table(labels);
  labels.clear();
  AddRotorLabels("true force", "N", n, &labels);
  AddRotorLabels("true thrust scale", "1", n, &labels);
  labels.insert(labels.end(), {"true x [m]", "true z [m]", "true pitch [rad]"});
  truth = Table(labels);
  labels.clear();
  AddRotorLabels("omega cmd", "rad/s", n, &labels);
  labels.insert(labels.end(), {"mode", "status [bits]"});
  motor_command = Table(labels);
}

std::vector<ForceFlag> ForceFlags(const FlightData& data) {
  std::vector<ForceFlag> flags;
  for (int i = 0; i < kStatusBitCount; ++i) {
    const StatusBitName& name = kStatusBitNames[i];
    if (name.bit == kStatusRotor2Fault) continue;  // expanded with rotor 1's
    if (name.bit != kStatusRotor1Fault) {
      flags.push_back({data.ForceStatusColumn(), name.bit, name.word, (kAlarmStatusBits & name.bit) != 0});
      continue;
    }
    for (int rotor = 0; rotor < data.rotor_count; ++rotor) {
      flags.push_back({data.ForceFaultColumn(), int32_t{1} << rotor, fmt::format("ROTOR{}_FAULT", rotor + 1), true});
    }
  }
  return flags;
}

FlightData::FlightData() {
  SetRotorCount(kBirotorRotors);
  std::vector<std::string> status_labels;
  for (const char* what : {"NIS mean", "fused", "rejected", "received"}) {
    for (const char* input : kReviewInputNames) status_labels.push_back(std::string(input) + " " + what);
  }
  status_labels.push_back("resets");
  status = Table(status_labels);
  pose = Table({"x [m]", "z [m]", "pitch [rad]"});
  imu = Table({"pitch rate [rad/s]"});
  controller_status = Table({"fallbacks", "descents", "saturated", "commands", "mode"});
  setpoint = Table({"x ref [m]", "z ref [m]"});
}

namespace {

// Decodes the channels the page shows; every message's time goes through
// Time(), which fixes t = 0 at the first decoded message.
class FlightDecoder {
 public:
  FlightDecoder(const std::string& prefix, FlightData* data) : channels_(MakeChannelNames(prefix)), data_(data) {}

  void Handle(const LogEvent& event) {
    ChannelCount& count = data_->channels[event.channel];
    ++count.messages;
    const std::string& c = event.channel;
    bool ok = true;
    if (c == channels_.force) {
      ok = Decode(event, &force_) && AddForce(ToCountedMessage(force_));
    } else if (c == channels_.force_n) {
      ok = Decode(event, &force_n_) && AddForce(force_n_);
    } else if (c == channels_.truth) {
      ok = Decode(event, &truth_) && AddTruth(ToCountedMessage(truth_));
    } else if (c == channels_.truth_n) {
      ok = Decode(event, &truth_n_) && AddTruth(truth_n_);
    } else if (c == channels_.estimator_status) {
      ok = Decode(event, &status_) && AddStatus();
    } else if (c == channels_.pose) {
      ok = Decode(event, &pose_);
      if (ok) data_->pose.Add(Time(pose_.utime), {pose_.x_m, pose_.z_m, pose_.phi_rad});
      if (ok) data_->input_t_s[3].push_back(Time(pose_.utime));
    } else if (c == channels_.motor_command) {
      ok = Decode(event, &command_) && AddCommand(ToCountedMessage(command_));
    } else if (c == channels_.motor_command_n) {
      ok = Decode(event, &command_n_) && AddCommand(command_n_);
    } else if (c == channels_.controller_status) {
      ok = Decode(event, &controller_);
      if (ok) {
        data_->controller_status.Add(
            Time(controller_.utime),
            {double(controller_.fallbacks), double(controller_.descents), double(controller_.saturated),
             double(controller_.commands), double(controller_.mode)});
      }
    } else if (c == channels_.setpoint) {
      ok = Decode(event, &setpoint_);
      if (ok) data_->setpoint.Add(Time(setpoint_.utime), {setpoint_.x_m, setpoint_.z_m});
      if (ok) data_->figures.AddSetpoint(FromMessage(setpoint_));
    } else if (c == channels_.imu) {
      ok = Decode(event, &imu_);
      if (ok) data_->imu.Add(Time(imu_.utime), {imu_.gyro_y_rad_s});
      if (ok) data_->input_t_s[2].push_back(Time(imu_.utime));
    } else if (c == channels_.strain || c == channels_.motor || c == channels_.strain_n || c == channels_.motor_n) {
      // Only the stamp: strain_t, motor_t and their counted twins start
      // with int64 utime after the 8-byte fingerprint.
      ok = event.data.size() >= 16;
      const bool strain = c == channels_.strain || c == channels_.strain_n;
      if (ok) data_->input_t_s[strain ? 0 : 1].push_back(Time(ReadUtime(event.data)));
    } else {
      return;  // counted only
    }
    if (!ok) ++count.decode_errors;
  }

 private:
  template <class Msg>
  bool Decode(const LogEvent& event, Msg* msg) {
    return DecodeMessage(event.data.data(), event.data.size(), msg) == DecodeError::kNone;
  }
  static int64_t ReadUtime(const std::vector<uint8_t>& bytes) {
    uint64_t value = 0;
    for (int i = 8; i < 16; ++i) value = (value << 8) | bytes[i];  // big-endian
    return static_cast<int64_t>(value);
  }
  double Time(int64_t utime) {
    if (!have_t0_) {
      data_->t0_utime = utime;
      have_t0_ = true;
    }
    const double t = 1e-6 * static_cast<double>(utime - data_->t0_utime);
    data_->duration_s = std::max(data_->duration_s, t);
    return t;
  }
  // Whether a counted message of n rotors fits the log's tables: the
  // first one lays them out (while they are empty); another count is
  // dropped and counted (arm 3 of a trirotor is not arm 3 of a quadrotor).
  bool AcceptCount(int n) {
    if (n < kBirotorRotors || n > kMaxArms) return false;
    FlightData& d = *data_;
    if (n != d.rotor_count && d.force.rows() == 0 && d.truth.rows() == 0 && d.motor_command.rows() == 0) {
      d.SetRotorCount(n);
    }
    if (n == d.rotor_count) return true;
    ++d.count_mismatches;
    return false;
  }
  bool AddForce(const force_estimate_n_t& m) {
    if (!AcceptCount(m.n_rotors)) return false;
    const int n = m.n_rotors;
    for (int i = 0; i < n; ++i) {
      row_[i] = m.force_n[i];
      row_[n + i] = m.force_std_n[i];
      row_[2 * n + i] = m.thrust_scale[i];
    }
    row_[3 * n] = double(m.status);
    row_[3 * n + 1] = double(m.rotor_fault_bits);
    data_->force.Add(Time(m.utime), row_, 3 * n + 2);
    return true;
  }
  bool AddTruth(const truth_n_t& m) {
    if (!AcceptCount(m.n_arms)) return false;
    const int n = m.n_arms;
    for (int i = 0; i < n; ++i) {
      row_[i] = m.force_n[i];
      row_[n + i] = m.thrust_scale[i];
    }
    row_[2 * n] = m.x_m;
    row_[2 * n + 1] = m.z_m;
    row_[2 * n + 2] = m.phi_rad;
    data_->truth.Add(Time(m.utime), row_, 2 * n + 3);
    data_->figures.AddTruth(BodyTruth(m));
    return true;
  }
  bool AddCommand(const motor_command_n_t& m) {
    if (!AcceptCount(m.n_rotors)) return false;
    const int n = m.n_rotors;
    for (int i = 0; i < n; ++i) row_[i] = m.omega_cmd_rad_s[i];
    row_[n] = double(m.mode);
    row_[n + 1] = double(m.status);
    data_->motor_command.Add(Time(m.utime), row_, n + 2);
    data_->figures.AddCommand(m.status);
    return true;
  }
  // The body's part of TRUTH_N, what the flight figures read (its arm
  // arrays are the birotor's only for n = 2 and are not read there).
  static TruthSample BodyTruth(const truth_n_t& m) {
    TruthSample body;
    body.utime = m.utime;
    body.x_m = m.x_m;
    body.z_m = m.z_m;
    body.phi_rad = m.phi_rad;
    body.x_dot_m_s = m.x_dot_m_s;
    body.z_dot_m_s = m.z_dot_m_s;
    body.phi_dot_rad_s = m.phi_dot_rad_s;
    return body;
  }
  bool AddStatus() {
    const std::vector<input_health_t>& inputs = status_.inputs;
    Table& table = data_->status;
    table.t_s.push_back(Time(status_.utime));
    size_t column = 0;
    auto input = [&](int i) -> const input_health_t& {
      return i < 4 ? (i < static_cast<int>(inputs.size()) ? inputs[i] : empty_) : status_.accelerometer;
    };
    for (int i = 0; i < kReviewInputs; ++i) table.columns[column++].push_back(input(i).nis_mean);
    for (int i = 0; i < kReviewInputs; ++i) table.columns[column++].push_back(double(input(i).fused));
    for (int i = 0; i < kReviewInputs; ++i) {
      table.columns[column++].push_back(double(input(i).rejected_gate + input(i).rejected_invalid));
    }
    for (int i = 0; i < kReviewInputs; ++i) table.columns[column++].push_back(double(input(i).received));
    table.columns[column++].push_back(double(status_.resets));
    return true;
  }

  const ChannelNames channels_;
  FlightData* data_;
  bool have_t0_ = false;
  force_estimate_t force_;
  force_estimate_n_t force_n_;
  truth_t truth_;
  truth_n_t truth_n_;
  estimator_status_t status_;
  pose_t pose_;
  imu_t imu_;
  motor_command_t command_;
  motor_command_n_t command_n_;
  double row_[3 * kMaxArms + 2] = {};  // one row of a per-rotor table
  controller_status_t controller_;
  setpoint_t setpoint_;
  const input_health_t empty_{};
};

}  // namespace

bool ReadFlightData(const std::string& path, const std::string& prefix, double min_usable_fraction, FlightData* data,
                    std::string* error) {
  *data = FlightData();
  data->path = path;
  LogReader reader;
  if (!reader.Open(path, error)) return false;
  FlightDecoder decoder(prefix, data);
  LogEvent event;
  std::map<std::string, int64_t> first_us, last_us;
  while (reader.Next(&event)) {
    ++data->events;
    decoder.Handle(event);
    // Channel times from the logger's receive stamps (every channel has one).
    auto [it, inserted] = first_us.emplace(event.channel, event.timestamp_us);
    (void)it;
    (void)inserted;
    last_us[event.channel] = event.timestamp_us;
  }
  if (!CheckLogUsable(reader, path, min_usable_fraction, error)) return false;
  int64_t log_t0_us = INT64_MAX;
  for (const auto& [name, us] : first_us) log_t0_us = std::min(log_t0_us, us);
  for (auto& [name, count] : data->channels) {
    count.first_s = 1e-6 * static_cast<double>(first_us[name] - log_t0_us);
    count.last_s = 1e-6 * static_cast<double>(last_us[name] - log_t0_us);
  }
  return true;
}

}  // namespace birotor
