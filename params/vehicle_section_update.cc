#include "params/vehicle_section_update.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <iomanip>
#include <set>
#include <sstream>
#include <vector>

#include "params/birotor_params_yaml.h"
#include "params/yaml_reader.h"

namespace birotor {
namespace {

std::vector<std::string> SplitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::string Number(double value) {
  std::ostringstream out;
  out << std::setprecision(10) << value;
  return out.str();
}

bool IsIndented(const std::string& line) { return !line.empty() && (line[0] == ' ' || line[0] == '\t'); }

bool IsBlankOrComment(const std::string& line) {
  const size_t first = line.find_first_not_of(" \t");
  return first == std::string::npos || line[first] == '#';
}

// Replaces the value of "<indent>key: value  # comment" with new_value,
// keeping the indent and the comment at its column when there is room.
std::string ReplaceValue(const std::string& line, size_t colon, const std::string& new_value) {
  const size_t hash = line.find('#', colon);
  std::string out = line.substr(0, colon + 1) + " " + new_value;
  if (hash != std::string::npos) {
    out += out.size() + 1 < hash ? std::string(hash - out.size(), ' ') : std::string("  ");
    out += line.substr(hash);
  }
  return out;
}

// The old value text in the form Number() writes ("4.0" -> "4", "[1.0, 1.0]"
// -> "[1, 1]"), to keep lines whose value does not change as they were.
std::string Normalized(const std::string& line, size_t colon) {
  const size_t hash = line.find('#', colon);
  std::string value = line.substr(colon + 1, hash == std::string::npos ? std::string::npos : hash - colon - 1);
  std::string out;
  std::string token;
  auto flush = [&]() {
    const size_t first = token.find_first_not_of(" \t");
    if (first == std::string::npos) {
      token.clear();
      return;
    }
    try {
      out += Number(std::stod(token.substr(first)));
    } catch (const std::exception&) {
      out += "?";
    }
    token.clear();
  };
  for (const char c : value) {
    if (c == '[' || c == ']' || c == ',') {
      flush();
      out += c == ',' ? std::string(", ") : std::string(1, c);
    } else {
      token += c;
    }
  }
  flush();
  return out;
}

}  // namespace

bool UpdateVehicleSection(const std::string& text, const BirotorParams& params, const std::string& stamp,
                          std::string* updated, std::string* error) {
  std::vector<std::string> lines = SplitLines(text);
  size_t header = lines.size();
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind("vehicle:", 0) == 0) {
      header = i;
      break;
    }
  }
  if (header == lines.size()) {
    *error = "no `vehicle:` section";
    return false;
  }
  // New values by key.
  std::vector<std::pair<std::string, std::string>> values;
  for (const VehicleKey& key : VehicleKeys()) values.emplace_back(key.name, Number(params.*key.field));
  values.emplace_back("gauge_scale", "[" + Number(params.gauge_scale[0]) + ", " + Number(params.gauge_scale[1]) + "]");
  values.emplace_back("gauge_offset_rad",
                      "[" + Number(params.gauge_offset_rad[0]) + ", " + Number(params.gauge_offset_rad[1]) + "]");
  std::set<std::string> done;
  size_t stamp_line = lines.size();
  size_t end = header + 1;
  std::string indent = "  ";
  for (; end < lines.size(); ++end) {
    std::string& line = lines[end];
    if (!IsIndented(line) && !IsBlankOrComment(line)) break;  // next top-level key
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    if (line.compare(first, std::string(kIdentificationStampPrefix).size(), kIdentificationStampPrefix) == 0) {
      stamp_line = end;
      continue;
    }
    if (line[first] == '#') continue;
    const size_t colon = line.find(':', first);
    if (colon == std::string::npos) continue;
    const std::string key = line.substr(first, colon - first);
    for (const auto& [name, value] : values) {
      if (name != key) continue;
      indent = line.substr(0, first);
      if (Normalized(line, colon) != value) line = ReplaceValue(line, colon, value);
      done.insert(name);
    }
  }
  for (const auto& [name, value] : values) {
    if (!done.count(name)) {
      *error = "vehicle key " + name + " missing (the file must be complete)";
      return false;
    }
  }
  if (!stamp.empty()) {
    const std::string stamp_text = indent + kIdentificationStampPrefix + stamp;
    if (stamp_line < lines.size()) {
      lines[stamp_line] = stamp_text;
    } else {
      lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(header) + 1, stamp_text);
    }
  }
  std::string out;
  for (const std::string& line : lines) out += line + "\n";
  *updated = out;
  return true;
}

std::string ReadIdentificationStamp(const std::string& file) {
  std::string text, error;
  if (!ReadRegularFile(file, kMaxParameterFileBytes, LinkPolicy::kFollow, &text, &error)) return "";
  std::istringstream in(text);
  std::string line;
  bool in_vehicle = false;
  while (std::getline(in, line)) {
    if (!IsIndented(line) && !IsBlankOrComment(line)) in_vehicle = line.rfind("vehicle:", 0) == 0;
    if (!in_vehicle) continue;
    const size_t first = line.find_first_not_of(" \t");
    const std::string prefix = kIdentificationStampPrefix;
    if (first != std::string::npos && line.compare(first, prefix.size(), prefix) == 0) {
      return line.substr(first + prefix.size());
    }
  }
  return "";
}

namespace {

// False with *error when the backup slot holds anything but a regular file.
bool BackupSlotFree(const std::string& backup, std::string* error) {
  std::string kind;
  if (InspectPath(backup, nullptr, &kind) != PathKind::kOther) return true;
  *error = backup + " exists and is " + kind + "; only a regular file is replaced there (remove it): refused";
  return false;
}

}  // namespace

bool PrepareParameterFileUpdate(const std::string& path, ParameterFileUpdate* update, std::string* error) {
  char resolved[PATH_MAX];
  if (::realpath(path.c_str(), resolved) == nullptr) {
    *error = path + ": cannot resolve: " + std::strerror(errno);
    return false;
  }
  update->path = path;
  update->target = resolved;
  update->backup = update->target + ".bak";
  if (!ReadRegularFile(update->target, kMaxParameterFileBytes, LinkPolicy::kRefuse, &update->text, error)) return false;
  struct stat info {};
  if (InspectPath(update->target, &update->attributes, nullptr) != PathKind::kRegular ||
      ::lstat(update->target.c_str(), &info) != 0) {
    *error = update->target + ": changed while checked: refused";
    return false;
  }
  update->device = info.st_dev;
  update->inode = info.st_ino;
  const std::string folder = update->target.substr(0, update->target.rfind('/') + 1);
  if (::access(folder.c_str(), W_OK) != 0) {
    *error = update->target + ": its folder " + folder + " is not writable: " + std::strerror(errno);
    return false;
  }
  return BackupSlotFree(update->backup, error);
}

bool CommitParameterFileUpdate(const ParameterFileUpdate& update, const std::string& updated_text, std::string* error) {
  std::string now;
  struct stat info {};
  if (::lstat(update.target.c_str(), &info) != 0 || !S_ISREG(info.st_mode) || info.st_dev != update.device ||
      info.st_ino != update.inode ||
      !ReadRegularFile(update.target, kMaxParameterFileBytes, LinkPolicy::kRefuse, &now, error) || now != update.text) {
    *error = update.target + ": replaced or changed since it was checked: left unchanged";
    return false;
  }
  if (!BackupSlotFree(update.backup, error)) return false;
  if (!ReplaceRegularFile(update.backup, update.text, update.attributes, error)) return false;
  return ReplaceRegularFile(update.target, updated_text, update.attributes, error);
}

}  // namespace birotor
