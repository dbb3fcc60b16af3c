// Building AUTH_STATUS (lcmtypes/auth_status_t.lcm): a program's signing
// sink and authenticating handler, one message. Used by the estimator and
// controller nodes with their status, and by birotor-sim.
#pragma once

#include <cstdint>

#include "birotor/auth_status_t.hpp"
#include "sinks/signing_sink.h"
#include "sources/authenticating_handler.h"

namespace birotor {

// Fills every field of *message but seq (the publisher's counter). signing
// or handler may be null (nothing sealed, nothing read).
void BuildAuthStatus(int32_t program, int64_t utime, int64_t wall_utime, const SigningSink* signing,
                     const AuthenticatingHandler* handler, auth_status_t* message);

}  // namespace birotor
