#include "program/config_files.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

namespace birotor {
namespace {

// <dir of the running executable>/../share/birotor/config, from /proc/self/exe
// (the real file, whatever link or relative path started it).
std::string ShippedConfigDir() {
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error || exe.empty()) return "share/birotor/config";
  return (exe.parent_path().parent_path() / "share" / "birotor" / "config").string();
}

std::string UserConfigDir() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  if (xdg != nullptr && xdg[0] == '/') return std::string(xdg) + "/birotor";
  const char* home = std::getenv("HOME");
  if (home != nullptr && home[0] == '/') return std::string(home) + "/.config/birotor";
  return "";
}

}  // namespace

std::vector<std::string> ConfigSearchDirs() {
  std::vector<std::string> dirs;
  const std::string user = UserConfigDir();
  if (!user.empty()) dirs.push_back(user);
  dirs.push_back("/etc/birotor");
  dirs.push_back(ShippedConfigDir());
  return dirs;
}

std::string FindConfigFile(const std::string& name) {
  const std::vector<std::string> dirs = ConfigSearchDirs();
  for (const std::string& dir : dirs) {
    const std::string path = dir + "/" + name;
    std::error_code error;
    if (std::filesystem::is_regular_file(path, error)) return path;
  }
  return dirs.back() + "/" + name;
}

std::string ConfigSearchText(const std::string& name) {
  std::string text;
  for (const std::string& dir : ConfigSearchDirs()) text += (text.empty() ? "" : ", ") + dir + "/" + name;
  return "first of " + text;
}

std::string ResolveScenario(const std::string& name_or_path) {
  const bool bare_name = name_or_path.find('/') == std::string::npos &&
                         (name_or_path.size() < 5 || name_or_path.substr(name_or_path.size() - 5) != ".yaml");
  return bare_name && !name_or_path.empty() ? FindConfigFile("scenarios/" + name_or_path + ".yaml") : name_or_path;
}

std::vector<std::string> ScenarioNames() {
  std::vector<std::string> names;
  for (const std::string& dir : ConfigSearchDirs()) {
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(dir + "/scenarios", error)) {
      if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
    }
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

bool FindScenario(const std::string& name_or_path_in, std::string* path, std::string* error) {
  const std::string name_or_path = name_or_path_in;  // path may be the argument itself
  *path = ResolveScenario(name_or_path);
  std::error_code exists_error;
  if (std::filesystem::is_regular_file(*path, exists_error)) return true;
  if (*path == name_or_path) {
    *error = name_or_path + ": no such scenario file";
    return false;
  }
  std::string names;
  for (const std::string& name : ScenarioNames()) names += (names.empty() ? "" : ", ") + name;
  *error = "unknown scenario '" + name_or_path + "' (scenarios: " + (names.empty() ? "none found" : names) +
           "; searched " + ConfigSearchText("scenarios/" + name_or_path + ".yaml") + ")";
  return false;
}

}  // namespace birotor
