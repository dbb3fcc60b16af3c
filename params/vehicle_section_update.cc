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

// The line of `vehicle:`; lines.size() with *error when there is none.
size_t VehicleHeader(const std::vector<std::string>& lines, std::string* error) {
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind("vehicle:", 0) == 0) return i;
  }
  *error = "no `vehicle:` section";
  return lines.size();
}

bool IsStampLine(const std::string& line, size_t first) {
  return line.compare(first, std::string(kIdentificationStampPrefix).size(), kIdentificationStampPrefix) == 0;
}

// The stamp line set to stamp (none when empty): replaced at stamp_line when
// the section has one, else inserted right below `vehicle:` at indent; then
// the lines joined.
std::string WithStamp(std::vector<std::string> lines, size_t header, size_t stamp_line, const std::string& indent,
                      const std::string& stamp) {
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
  return out;
}

}  // namespace

bool UpdateVehicleSection(const std::string& text, const BirotorParams& params, const std::string& stamp,
                          std::string* updated, std::string* error) {
  std::vector<std::string> lines = SplitLines(text);
  const size_t header = VehicleHeader(lines, error);
  if (header == lines.size()) return false;
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
    if (IsStampLine(line, first)) {
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
  *updated = WithStamp(lines, header, stamp_line, indent, stamp);
  return true;
}

bool UpdateDescriptionArmValues(const std::string& text, const std::string& key, const std::vector<double>& values,
                                const std::string& stamp, std::string* updated, std::string* error) {
  std::vector<std::string> lines = SplitLines(text);
  const size_t header = VehicleHeader(lines, error);
  if (header == lines.size()) return false;
  constexpr size_t kOutside = std::string::npos;
  size_t stamp_line = lines.size(), arms_column = kOutside;  // kOutside: not in the `arms:` list
  std::string indent = "  ";
  int arm = -1;
  std::vector<int> found(values.size(), 0);
  for (size_t i = header + 1; i < lines.size(); ++i) {
    std::string& line = lines[i];
    if (!IsIndented(line) && !IsBlankOrComment(line)) break;  // next top-level key
    size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    if (IsStampLine(line, first)) stamp_line = i;
    if (line[first] == '#') continue;
    // A key at or left of `arms:` ends the list; its dashes may sit at its column.
    if (arms_column != kOutside && first <= arms_column && line[first] != '-') arms_column = kOutside;
    if (arms_column == kOutside) {
      indent = line.substr(0, first);
      if (line.compare(first, 5, "arms:") == 0) arms_column = first;
      continue;
    }
    if (line[first] == '-') {  // "- key: value" opens the next arm
      ++arm;
      first = line.find_first_not_of(" \t", first + 1);
      if (first == std::string::npos || line[first] == '#') continue;
    }
    const size_t colon = line.find(':', first);
    if (colon == std::string::npos || line.substr(first, colon - first) != key) continue;
    if (arm < 0 || arm >= static_cast<int>(values.size())) break;  // reported below as a count
    ++found[static_cast<size_t>(arm)];
    const std::string value = Number(values[static_cast<size_t>(arm)]);
    if (Normalized(line, colon) != value) line = ReplaceValue(line, colon, value);
  }
  if (arm + 1 != static_cast<int>(values.size())) {
    *error = "vehicle.arms: not a block list of " + std::to_string(values.size()) + " arms";
    return false;
  }
  for (size_t i = 0; i < found.size(); ++i) {
    if (found[i] != 1) {
      *error = "vehicle.arms[" + std::to_string(i) + "]." + key + (found[i] == 0 ? " missing" : " given twice");
      return false;
    }
  }
  *updated = WithStamp(lines, header, stamp_line, indent, stamp);
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
