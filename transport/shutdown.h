// Cooperative shutdown on SIGINT/SIGTERM: the handler only sets a flag that
// the main loop polls between handleTimeout calls. A second signal while the
// first is still pending ends the program at once (for a hung loop).
#pragma once

namespace birotor {

// Installs the handlers for SIGINT and SIGTERM (idempotent).
void InstallShutdownHandlers();

// True once a signal arrived or RequestShutdown was called.
bool ShutdownRequested();

// Sets the flag as a signal would (tests, or a program ending itself).
void RequestShutdown();

// Clears the flag (tests only).
void ClearShutdownRequest();

}  // namespace birotor
