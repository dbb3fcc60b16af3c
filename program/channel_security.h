// What a daemon needs to authenticate its channels (docs/deploy.md, "The site
// key"): the site key file (--site-key) and the channels the site lets
// through unsigned (--unsigned), read once at start-up. A daemon that
// publishes or reads an authenticated channel the site has not let through
// unsigned does not start without a readable key: a vehicle never falls back
// to unauthenticated commands because a file is missing.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "security/message_authenticator.h"
#include "transport/authenticated_envelope.h"

namespace birotor {

inline constexpr char kDefaultSiteKeyFile[] = "/etc/birotor/keys/site.key";

struct ChannelSecurityOptions {
  std::string site_key_file = kDefaultSiteKeyFile;
  // Comma-separated base names (MOTOR_COMMAND, SETPOINT, POSE, FORCE,
  // MOTOR_COMMAND_N, FORCE_N), "all"
  // or "none": published plain and accepted plain.
  std::string unsigned_channels = "none";
};

// Adds --site-key and --unsigned to app.
void AddChannelSecurityOptions(CLI::App& app, ChannelSecurityOptions* options);

struct ChannelSecurity {
  std::unique_ptr<MessageAuthenticator> authenticator;  // null: no key read (every used channel unsigned)
  ChannelSet unsigned_channels{};                       // true: plain on the wire
  std::string key_problem;                              // why no key was read ("site key FILE: reason"); "" with a key
  ChannelSet signed_channels() const;                   // the complement; none without a key
};

// Reads the key unless every channel in used is let through unsigned; then
// the key is read only if it is there (a state file may still need it).
// False with *error naming the key file, the reason and the channels that
// need it.
bool LoadChannelSecurity(const ChannelSecurityOptions& options, const ChannelSet& used, ChannelSecurity* security,
                         std::string* error);

}  // namespace birotor
