// libFuzzer harness for the LCM log-file reader (transport/log_io.h): the
// input is a whole log file (in a memfd, a real regular file). Nothing may
// crash, allocate more than the file holds, or read an event that does not
// fit in the file; the reader's book-keeping must add up.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "transport/log_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const int fd = memfd_create("log_reader_fuzzer", MFD_CLOEXEC);
  if (fd < 0) return 0;
  size_t written = 0;
  while (written < size) {
    const ssize_t n = write(fd, data + written, size - written);
    if (n <= 0) {
      close(fd);
      return 0;
    }
    written += static_cast<size_t>(n);
  }
  birotor::LogReader reader;
  std::string error;
  if (!reader.OpenDescriptor(fd, "fuzz.lcm", &error)) {
    if (error.empty()) std::abort();
    return 0;
  }
  const int64_t file_size = static_cast<int64_t>(size);
  birotor::LogEvent event;
  int64_t bytes = 0;
  int64_t events = 0;
  while (reader.Next(&event)) {
    ++events;
    if (event.channel.empty() || event.channel.size() > static_cast<size_t>(birotor::kLogMaxChannelBytes)) {
      std::abort();
    }
    bytes += birotor::kLogEventHeaderBytes + static_cast<int64_t>(event.channel.size() + event.data.size());
    if (bytes > file_size) std::abort();
  }
  if (events != reader.events_read() || bytes != reader.event_bytes()) std::abort();
  if (reader.event_bytes() + reader.skipped_bytes() > file_size) std::abort();
  if (reader.tail_offset() > reader.file_size() || reader.file_size() != file_size) std::abort();
  if (events == 0 && file_size > 0 && !reader.TruncatedTail()) std::abort();
  return 0;
}
