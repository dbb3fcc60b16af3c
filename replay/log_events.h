// The read loop both log loaders share (identification_log_loader.cc for
// the birotor's channels, multi_arm_log_loader.cc for N arms): every event
// of an lcm-logger file to a handler, counted, then the file's tail figures
// and its usability (CheckLogUsable of transport/log_io.h).
#pragma once

#include <string>

#include "replay/identification_log_loader.h"
#include "transport/lcm_codec.h"
#include "transport/log_io.h"

namespace birotor {

// Decodes the event as Msg: false, counted in report->decode_errors, when
// its bytes are not one.
template <class Msg>
bool DecodeCounted(const LogEvent& event, Msg* message, LogLoadReport* report) {
  if (DecodeMessage(event.data.data(), event.data.size(), message) == DecodeError::kNone) return true;
  ++report->decode_errors;
  return false;
}

// Opens the log at path, resets *report and hands every event to
// on_event(const LogEvent&) -> bool (false: stop, on_event has set *error),
// counting them; then fills the tail figures and checks the log is usable.
// False with a one-line *error when the file cannot be opened, on_event
// stopped or the log is not usable.
template <class OnEvent>
bool ReadLogEvents(const std::string& path, double min_usable_fraction, LogLoadReport* report, std::string* error,
                   OnEvent on_event) {
  LogReader reader;
  if (!reader.Open(path, error)) return false;
  *report = LogLoadReport();
  LogEvent event;
  while (reader.Next(&event)) {
    ++report->events;
    if (!on_event(event)) return false;
  }
  report->truncated_tail = reader.TruncatedTail();
  report->tail_offset = reader.tail_offset();
  report->file_size = reader.file_size();
  return CheckLogUsable(reader, path, min_usable_fraction, error, &report->damage);
}

}  // namespace birotor
