#include "review/flight_data.h"

#include <algorithm>
#include <string_view>

#include "birotor/controller_status_t.hpp"
#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/motor_command_t.hpp"
#include "birotor/pose_t.hpp"
#include "birotor/setpoint_t.hpp"
#include "birotor/truth_t.hpp"
#include "transport/channels.h"
#include "transport/lcm_codec.h"
#include "transport/log_io.h"
#include "transport/message_conversion.h"

namespace birotor {

const char* const kReviewInputNames[kReviewInputs] = {"STRAIN", "MOTOR", "IMU", "POSE", "IMU accel_z"};

void Table::Add(double t, std::initializer_list<double> values) {
  t_s.push_back(t);
  size_t c = 0;
  for (const double value : values) columns[c++].push_back(value);
}

FlightData::FlightData() {
  force = Table({"force 1 [N]", "force 2 [N]", "sigma 1 [N]", "sigma 2 [N]", "thrust scale 1 [1]", "thrust scale 2 [1]",
                 "status [bits]"});
  truth = Table({"true force 1 [N]", "true force 2 [N]", "true thrust scale 1 [1]", "true thrust scale 2 [1]",
                 "true x [m]", "true z [m]", "true pitch [rad]"});
  std::vector<std::string> status_labels;
  for (const char* what : {"NIS mean", "fused", "rejected", "received"}) {
    for (const char* input : kReviewInputNames) status_labels.push_back(std::string(input) + " " + what);
  }
  status_labels.push_back("resets");
  status = Table(status_labels);
  pose = Table({"x [m]", "z [m]", "pitch [rad]"});
  imu = Table({"pitch rate [rad/s]"});
  motor_command = Table({"omega cmd 1 [rad/s]", "omega cmd 2 [rad/s]", "mode", "status [bits]"});
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
      ok = Decode(event, &force_) && AddForce();
    } else if (c == channels_.truth) {
      ok = Decode(event, &truth_) && AddTruth();
    } else if (c == channels_.estimator_status) {
      ok = Decode(event, &status_) && AddStatus();
    } else if (c == channels_.pose) {
      ok = Decode(event, &pose_);
      if (ok) data_->pose.Add(Time(pose_.utime), {pose_.x_m, pose_.z_m, pose_.phi_rad});
      if (ok) data_->input_t_s[3].push_back(Time(pose_.utime));
    } else if (c == channels_.motor_command) {
      ok = Decode(event, &command_);
      if (ok) {
        data_->motor_command.Add(Time(command_.utime), {command_.omega_cmd_rad_s[0], command_.omega_cmd_rad_s[1],
                                                        double(command_.mode), double(command_.status)});
        data_->figures.AddCommand(command_.status);
      }
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
    } else if (c == channels_.strain || c == channels_.motor) {
      // Only the stamp: strain_t and motor_t start with int64 utime after
      // the 8-byte fingerprint.
      ok = event.data.size() >= 16;
      if (ok) data_->input_t_s[c == channels_.strain ? 0 : 1].push_back(Time(ReadUtime(event.data)));
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
  bool AddForce() {
    data_->force.Add(Time(force_.utime),
                     {force_.force_n[0], force_.force_n[1], force_.force_std_n[0], force_.force_std_n[1],
                      force_.thrust_scale[0], force_.thrust_scale[1], double(force_.status)});
    return true;
  }
  bool AddTruth() {
    data_->truth.Add(Time(truth_.utime), {truth_.force_n[0], truth_.force_n[1], truth_.thrust_scale[0],
                                          truth_.thrust_scale[1], truth_.x_m, truth_.z_m, truth_.phi_rad});
    data_->figures.AddTruth(FromMessage(truth_));
    return true;
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
  truth_t truth_;
  estimator_status_t status_;
  pose_t pose_;
  imu_t imu_;
  motor_command_t command_;
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
