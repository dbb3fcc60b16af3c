#include "program/channel_security.h"

#include "security/site_key.h"

namespace birotor {

void AddChannelSecurityOptions(CLI::App& app, ChannelSecurityOptions* options) {
  app.add_option("--site-key", options->site_key_file,
                 "Site key file (32 raw bytes, not group/world-writable) that authenticates MOTOR_COMMAND, SETPOINT, "
                 "POSE, FORCE, MOTOR_COMMAND_N and FORCE_N (their _AUTH channels) and the gauge state file")
      ->capture_default_str();
  app.add_option("--unsigned", options->unsigned_channels,
                 "Channels this site lets through unauthenticated (comma-separated MOTOR_COMMAND, SETPOINT, POSE, "
                 "FORCE, MOTOR_COMMAND_N, FORCE_N, or all, or none): published and accepted plain")
      ->capture_default_str();
}

ChannelSet ChannelSecurity::signed_channels() const {
  ChannelSet set{};
  if (!authenticator) return set;
  for (int i = 0; i < kNumAuthenticatedChannels; ++i) set[i] = !unsigned_channels[i];
  return set;
}

bool LoadChannelSecurity(const ChannelSecurityOptions& options, const ChannelSet& used, ChannelSecurity* security,
                         std::string* error) {
  std::string parse_error;
  if (!ParseChannelSet(options.unsigned_channels, &security->unsigned_channels, &parse_error)) {
    *error = "--unsigned: " + parse_error;
    return false;
  }
  std::string needing;  // the used channels that are authenticated, "POSE, FORCE"
  const ChannelNames names = MakeChannelNames("");
  for (int i = 0; i < kNumAuthenticatedChannels; ++i) {
    if (used[i] && !security->unsigned_channels[i]) {
      needing += std::string(needing.empty() ? "" : ", ") + NamesOf(names, static_cast<AuthenticatedChannel>(i)).base;
    }
  }
  SiteKey key(SiteKey::Bytes{});
  std::string key_error;
  if (SiteKey::Load(options.site_key_file, &key, &key_error)) {
    security->authenticator = std::make_unique<MessageAuthenticator>(key);
    return true;
  }
  security->key_problem = key_error;
  if (needing.empty()) return true;
  *error = key_error + "; it authenticates " + needing +
           " (docs/deploy.md, \"The site key\"): install the key, give its path with --site-key, or let the "
           "channels through with --unsigned";
  return false;
}

}  // namespace birotor
