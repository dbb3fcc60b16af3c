#include "nodes/gauge_state_file.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "params/vehicle_params_yaml.h"
#include "program/logging.h"

namespace birotor {
namespace {

constexpr const char* kHeader = "# birotor-estimator gauge offset state\n";

// Two finite numbers from "a b"; false otherwise.
bool ParsePair(const std::string& text, double out[2]) {
  std::istringstream in(text);
  std::string extra;
  if (!(in >> out[0] >> out[1]) || (in >> extra)) return false;
  return std::isfinite(out[0]) && std::isfinite(out[1]);
}

}  // namespace

std::string VehicleChecksum(const VehicleParams& params) { return TextChecksum(VehicleParamsYaml(params)); }

std::string GaugeStateText(const GaugeCalibration& calibration, const std::string& vehicle_checksum) {
  char body[512];
  std::snprintf(body, sizeof(body),
                "%svehicle_checksum: %s\ngauge_offset_rad: %.17g %.17g\ngauge_offset_std_rad: %.17g %.17g\n", kHeader,
                vehicle_checksum.c_str(), calibration.offset_rad[0], calibration.offset_rad[1],
                calibration.offset_std_rad[0], calibration.offset_std_rad[1]);
  return std::string(body) + "checksum: " + TextChecksum(body) + "\n";
}

bool WriteGaugeState(const std::string& path, const GaugeCalibration& calibration, const std::string& vehicle_checksum,
                     std::string* error) {
  const std::string temp = path + ".tmp";
  const std::string text = GaugeStateText(calibration, vehicle_checksum);
  std::FILE* file = std::fopen(temp.c_str(), "w");
  if (file == nullptr) {
    *error = "cannot write " + temp;
    return false;
  }
  const bool written = std::fwrite(text.data(), 1, text.size(), file) == text.size();
  const bool closed = std::fclose(file) == 0;
  if (!written || !closed || std::rename(temp.c_str(), path.c_str()) != 0) {
    std::remove(temp.c_str());
    *error = "cannot write " + path;
    return false;
  }
  return true;
}

bool ReadGaugeState(const std::string& path, const std::string& vehicle_checksum, double max_offset_rad,
                    GaugeCalibration* calibration, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *error = path + ": cannot read";
    return false;
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  if (text.size() > 4096) {
    *error = path + ": corrupt (larger than a state file)";
    return false;
  }
  const size_t checksum_at = text.rfind("checksum: ");
  if (checksum_at == std::string::npos || checksum_at == 0 || text[checksum_at - 1] != '\n' ||
      text.compare(0, std::char_traits<char>::length(kHeader), kHeader) != 0) {
    *error = path + ": corrupt (not a gauge state file)";
    return false;
  }
  const std::string body = text.substr(0, checksum_at);
  std::string stated = text.substr(checksum_at + 10);
  while (!stated.empty() && (stated.back() == '\n' || stated.back() == '\r')) stated.pop_back();
  if (stated != TextChecksum(body)) {
    *error = path + ": corrupt (checksum mismatch)";
    return false;
  }
  std::map<std::string, std::string> fields;
  std::istringstream lines(body);
  for (std::string line; std::getline(lines, line);) {
    const size_t colon = line.find(": ");
    if (line.empty() || line[0] == '#' || colon == std::string::npos) continue;
    fields[line.substr(0, colon)] = line.substr(colon + 2);
  }
  if (fields["vehicle_checksum"] != vehicle_checksum) {
    *error = path + ": written for another vehicle or parameter file (vehicle checksum " + fields["vehicle_checksum"] +
             ", expected " + vehicle_checksum + ")";
    return false;
  }
  double offset[2], std_rad[2];
  if (!ParsePair(fields["gauge_offset_rad"], offset) || !ParsePair(fields["gauge_offset_std_rad"], std_rad) ||
      std::abs(offset[0]) > max_offset_rad || std::abs(offset[1]) > max_offset_rad || std_rad[0] <= 0 ||
      std_rad[1] <= 0) {
    *error = path + ": corrupt (gauge_offset_rad or gauge_offset_std_rad missing or out of range)";
    return false;
  }
  for (int i = 0; i < 2; ++i) {
    calibration->offset_rad[i] = offset[i];
    calibration->offset_std_rad[i] = std_rad[i];
  }
  calibration->source = GaugeOffsetSource::kStateFile;
  return true;
}

}  // namespace birotor
