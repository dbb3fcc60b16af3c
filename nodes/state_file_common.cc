#include "nodes/state_file_common.h"

#include <sodium.h>

#include <cmath>
#include <sstream>

#include "params/birotor_params_yaml.h"
#include "program/logging.h"

namespace birotor {
namespace {

constexpr const char* kMacKey = "mac: ";
constexpr size_t kMacKeyLength = 5;
constexpr const char* kChecksumKey = "checksum: ";
constexpr size_t kChecksumKeyLength = 10;

bool StartsWith(const std::string& text, const char* prefix) {
  return text.compare(0, std::char_traits<char>::length(prefix), prefix) == 0;
}

// The header line without its newline, for a message.
std::string HeaderLine(const char* header) { return std::string(header, std::char_traits<char>::length(header) - 1); }

}  // namespace

StateFileKind StateFileKindOf(const std::string& text) {
  if (StartsWith(text, kBirotorStateHeader)) return StateFileKind::kBirotor;
  if (StartsWith(text, kVehicleStateHeader)) return StateFileKind::kVehicle;
  return StateFileKind::kNone;
}

const char* StateFileKindName(StateFileKind kind) {
  switch (kind) {
    case StateFileKind::kBirotor:
      return "a birotor gauge state file (birotor-estimator without --vehicle)";
    case StateFileKind::kVehicle:
      return "a gauge state file of a vehicle with N arms (birotor-estimator --vehicle)";
    case StateFileKind::kNone:
      break;
  }
  return "not a gauge state file";
}

StateValueRange VehicleKeyRange(const char* name) {
  for (const VehicleKey& key : VehicleKeys()) {
    if (std::string(key.name) == name) return {key.min, key.max};
  }
  return {0.0, 0.0};
}

StateValueRange GaugeOffsetStdRange() { return VehicleKeyRange("gauge_offset_std_rad"); }

bool ParseFiniteNumbers(const std::string& text, int n, double* out) {
  std::istringstream in(text);
  for (int i = 0; i < n; ++i) {
    if (!(in >> out[i]) || !std::isfinite(out[i])) return false;
  }
  std::string extra;
  return !(in >> extra);
}

std::string StateFileMacLine(const std::string& text, const MessageAuthenticator& authenticator) {
  const MessageAuthenticator::Tag tag =
      authenticator.Sign(0, reinterpret_cast<const uint8_t*>(text.data()), text.size());
  char hex[2 * MessageAuthenticator::kTagBytes + 1];
  sodium_bin2hex(hex, sizeof(hex), tag.data(), tag.size());
  return std::string(kMacKey) + hex + "\n";
}

size_t StateFileMacLineStart(const std::string& text) {
  const size_t at = text.rfind(kMacKey);
  if (at == std::string::npos || at == 0 || text[at - 1] != '\n') return std::string::npos;
  return text.find('\n', at) >= text.size() - 1 ? at : std::string::npos;
}

bool VerifyStateFileMac(const std::string& path, const MessageAuthenticator& authenticator, std::string* text,
                        std::string* error) {
  const size_t at = StateFileMacLineStart(*text);
  if (at == std::string::npos) {
    *error = path + ": not authenticated (no mac line; written without the site key or forged)";
    return false;
  }
  std::string hex = text->substr(at + kMacKeyLength);
  while (!hex.empty() && (hex.back() == '\n' || hex.back() == '\r')) hex.pop_back();
  MessageAuthenticator::Tag tag;
  size_t decoded = 0;
  if (sodium_hex2bin(tag.data(), tag.size(), hex.c_str(), hex.size(), nullptr, &decoded, nullptr) != 0 ||
      decoded != tag.size() || hex.size() != 2 * tag.size() ||
      !authenticator.Verify(0, reinterpret_cast<const uint8_t*>(text->data()), at, tag)) {
    *error = path + ": not authenticated (mac does not verify under the site key: forged, altered or another key)";
    return false;
  }
  text->resize(at);
  return true;
}

bool ReadStateFileText(const std::string& path, const MessageAuthenticator* authenticator, std::string* text,
                       std::string* error) {
  if (!ReadRegularFile(path, kMaxStateFileBytes, LinkPolicy::kRefuse, text, error)) return false;
  if (authenticator != nullptr) return VerifyStateFileMac(path, *authenticator, text, error);
  const size_t mac_at = StateFileMacLineStart(*text);
  if (mac_at != std::string::npos) text->resize(mac_at);
  return true;
}

bool ChecksummedStateFields(const std::string& path, const std::string& text, const char* header,
                            std::map<std::string, std::string>* fields, std::string* error) {
  const StateFileKind kind = StateFileKindOf(text);
  if (kind != StateFileKind::kNone && kind != StateFileKindOf(header)) {
    *error =
        path + ": is " + StateFileKindName(kind) + ", not " + StateFileKindName(StateFileKindOf(header)) + ": refused";
    return false;
  }
  const size_t checksum_at = text.rfind(kChecksumKey);
  if (checksum_at == std::string::npos || checksum_at == 0 || text[checksum_at - 1] != '\n' ||
      !StartsWith(text, header)) {
    *error = path + ": corrupt (not a gauge state file)";
    return false;
  }
  const std::string body = text.substr(0, checksum_at);
  std::string stated = text.substr(checksum_at + kChecksumKeyLength);
  while (!stated.empty() && (stated.back() == '\n' || stated.back() == '\r')) stated.pop_back();
  if (stated != TextChecksum(body)) {
    *error = path + ": corrupt (checksum mismatch)";
    return false;
  }
  std::istringstream lines(body);
  for (std::string line; std::getline(lines, line);) {
    const size_t colon = line.find(": ");
    if (line.empty() || line[0] == '#' || colon == std::string::npos) continue;
    (*fields)[line.substr(0, colon)] = line.substr(colon + 2);
  }
  return true;
}

bool ReplaceableStateFile(const std::string& path, const char* header, FileAttributes* attributes, std::string* error) {
  // Only a state file of this kind is replaced: an existing path that is a
  // link, a FIFO, a device, another file (the parameter file given as
  // state_file) or the other kind's state file is left alone.
  std::string kind;
  switch (InspectPath(path, attributes, &kind)) {
    case PathKind::kOther:
      *error = path + ": exists and is " + kind + ", not a gauge state file: not overwritten";
      return false;
    case PathKind::kRegular: {
      std::string old_text;
      if (!ReadRegularFile(path, kMaxStateFileBytes, LinkPolicy::kRefuse, &old_text, error)) {
        *error += ": not a gauge state file, not overwritten";
        return false;
      }
      const StateFileKind old_kind = StateFileKindOf(old_text);
      if (old_kind != StateFileKind::kNone && old_kind != StateFileKindOf(header)) {
        *error = path + ": exists and is " + StateFileKindName(old_kind) + ": not overwritten";
        return false;
      }
      if (!StartsWith(old_text, header)) {
        *error =
            path + ": exists and is not a gauge state file (no '" + HeaderLine(header) + "' line): not overwritten";
        return false;
      }
      return true;
    }
    case PathKind::kAbsent:
      *attributes = FileAttributes();  // 0644, the writer's user
      return true;
  }
  return false;
}

}  // namespace birotor
