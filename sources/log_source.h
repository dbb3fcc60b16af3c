// The log-file source (replay, tests, fuzzers): every event of an LCM log
// (transport/log_io.h's checked reader) on a subscribed channel goes to the
// handler, with the logger's recorded time as the receive time, as fast as
// the handler takes them.
#pragma once

#include <string>
#include <vector>

#include "sources/message_source.h"
#include "transport/log_io.h"

namespace birotor {

class LogSource : public MessageSource {
 public:
  // Opens the log; false (with a one-line *error) as LogReader::Open.
  bool Open(const std::string& path, std::string* error) { return reader_.Open(path, error); }
  // Over an open descriptor (memfd in the fuzzers), owned by the source.
  bool OpenDescriptor(int fd, const std::string& name, std::string* error) {
    return reader_.OpenDescriptor(fd, name, error);
  }

  // An empty list subscribes to every channel (replay copies TRUTH through).
  bool Subscribe(const std::vector<std::string>& channels, PacketHandler* handler, std::string* error) override;
  bool Wait(double /*timeout_s*/) override { return !finished_; }
  bool DeliverOne() override;
  bool finished() const override { return finished_; }
  std::string Describe() const override { return "LCM log file"; }

  // The reader, for CheckLogUsable once the source is finished.
  const LogReader& reader() const { return reader_; }

 private:
  LogReader reader_;
  LogEvent event_;
  std::vector<std::string> channels_;
  PacketHandler* handler_ = nullptr;
  bool finished_ = false;
};

}  // namespace birotor
