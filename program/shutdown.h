// The daemons' signals. SIGINT/SIGTERM: cooperative shutdown (the handler
// only sets a flag that the main loop polls, so the program stops cleanly and
// writes what it keeps, such as the gauge state file; another signal more
// than 1 s after the first, the loop not stopped yet, ends the program at
// once, for a hung loop; one within 1 s is the same stop asked twice, as GNU
// timeout does by signalling the program and then its process group). SIGHUP,
// SIGUSR1, SIGUSR2, SIGALRM: no meaning for these programs (they log to
// stderr only, so there is no log file to re-open on HUP); counted and said
// in the log instead of ending the process (their default action).
// SIGPIPE: ignored, so a closed log reader gives EPIPE on the write (which
// the logger drops) instead of killing the process.
#pragma once

#include <string>

namespace birotor {

// Installs the handlers for SIGINT, SIGTERM, SIGHUP, SIGUSR1, SIGUSR2,
// SIGALRM and ignores SIGPIPE (idempotent).
void InstallShutdownHandlers();

// True once a signal arrived or RequestShutdown was called.
bool ShutdownRequested();

// Sets the flag as a signal would (tests, or a program ending itself).
void RequestShutdown();

// Clears the flag (tests only).
void ClearShutdownRequest();

// "SIGHUP x2, SIGUSR1 x1 ignored" for the ignored signals that arrived since
// the last call, "" if none (the receive loop logs it).
std::string TakeIgnoredSignalReport();

// Makes sure descriptors 0, 1 and 2 are open (on /dev/null when a parent
// closed them), so that no socket or pipe opened later takes their number
// and receives the log lines written to stderr. Call first in main.
void KeepStandardStreamsOpen();

}  // namespace birotor
