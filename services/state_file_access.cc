#include "services/state_file_access.h"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <filesystem>

namespace birotor {

const MessageAuthenticator* StateFileAuthenticator(const ChannelSecurity& security, const std::string& state_file) {
  if (state_file.empty()) return nullptr;
  if (!security.authenticator) {
    spdlog::warn("gauge state file {} is not authenticated ({}): neither restored nor written this run", state_file,
                 security.key_problem);
  }
  return security.authenticator.get();
}

std::string WritableStateFile(const std::string& state_file) {
  if (state_file.empty()) return "";
  const std::string folder = std::filesystem::path(state_file).parent_path().string();
  if (access(folder.empty() ? "." : folder.c_str(), W_OK) == 0) return state_file;
  spdlog::warn(
      "gauge offsets will not be persisted: {} is missing or not writable by this user (the systemd unit's "
      "StateDirectory= provides it; started by hand, create it or give --params a file with another "
      "tare.state_file)",
      folder.empty() ? "." : folder);
  return "";
}

}  // namespace birotor
