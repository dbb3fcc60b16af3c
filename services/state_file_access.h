// Whether a daemon of birotor-estimator (the birotor's, or --vehicle for N
// arms) may restore and write its gauge state file (tare.state_file): the
// site key that authenticates it, and a folder it can write at its stop.
#pragma once

#include <string>

#include "program/channel_security.h"
#include "security/message_authenticator.h"

namespace birotor {

// The authenticator of the gauge state file, or null after one warning when
// a state file is configured and no key was read (POSE and FORCE both let
// through unsigned): the state file is then neither restored nor written (an
// unauthenticated file could be forged).
const MessageAuthenticator* StateFileAuthenticator(const ChannelSecurity& security, const std::string& state_file);

// The state file the offsets are written to at a clean stop: the configured
// one if its folder is writable, else "" after one warning at start. Under
// systemd the folder is the unit's StateDirectory (/var/lib/birotor, made for
// its DynamicUser); a daemon started by hand has none, and runs without
// persisting instead of failing at its stop (issue 39).
std::string WritableStateFile(const std::string& state_file);

}  // namespace birotor
