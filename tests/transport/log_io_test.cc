// Tests of transport/log_io.h: write/read round trip, compatibility with
// LCM's own log readers (lcm::LogFile, the file:// provider, lcm-logplayer),
// and a log cut mid-event.
#include "transport/log_io.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "tests/transport/test_files.h"
#include "tests/transport/test_messages.h"

namespace birotor {
namespace {

using transport_test::MakeTestMessage;

using test_files::HugeDataLengthLog;
using test_files::LogEventHeader;
using test_files::ReadBytes;
using test_files::WriteBytes;

// A fresh temporary directory per test.
class LogIoTest : public test_files::TempDirTest {};

// The events WriteExampleLog writes, in order.
struct Expected {
  std::string channel;
  int64_t timestamp_us;
  std::vector<uint8_t> data;
};

std::vector<Expected> WriteExampleLog(const std::string& path) {
  std::vector<Expected> expected;
  LogWriter writer;
  std::string error;
  EXPECT_TRUE(writer.Open(path, &error)) << error;
  for (int i = 0; i < 20; ++i) {
    strain_t strain = MakeTestMessage<strain_t>();
    strain.utime = 1000 * i;
    strain.seq = i;
    std::vector<uint8_t> bytes;
    EncodeMessage(strain, &bytes);
    EXPECT_TRUE(writer.WriteMessage("BIROTOR_STRAIN", 1000 * i + 7, strain));
    expected.push_back({"BIROTOR_STRAIN", 1000 * i + 7, bytes});
    if (i % 2 == 0) {
      const std::vector<uint8_t> raw = {1, 2, 3, static_cast<uint8_t>(i)};
      EXPECT_TRUE(writer.Write("RAW", 1000 * i + 8, raw.data(), raw.size()));
      expected.push_back({"RAW", 1000 * i + 8, raw});
    }
  }
  EXPECT_EQ(writer.events_written(), static_cast<int64_t>(expected.size()));
  EXPECT_TRUE(writer.Close());
  return expected;
}

std::vector<LogEvent> ReadAll(LogReader* reader) {
  std::vector<LogEvent> events;
  LogEvent event;
  while (reader->Next(&event)) events.push_back(event);
  return events;
}

void ExpectEvents(const std::vector<LogEvent>& events, const std::vector<Expected>& expected, size_t count) {
  ASSERT_EQ(events.size(), count);
  for (size_t i = 0; i < count; ++i) {
    EXPECT_EQ(events[i].event_number, static_cast<int64_t>(i));
    EXPECT_EQ(events[i].channel, expected[i].channel);
    EXPECT_EQ(events[i].timestamp_us, expected[i].timestamp_us);
    EXPECT_EQ(events[i].data, expected[i].data);
  }
}

// Byte offset of the end of each event of the log at path.
std::vector<int64_t> EventEnds(const std::string& path) {
  std::vector<int64_t> ends;
  LogReader reader;
  std::string error;
  EXPECT_TRUE(reader.Open(path, &error)) << error;
  LogEvent event;
  while (reader.Next(&event)) ends.push_back(reader.tail_offset());
  return ends;
}

TEST_F(LogIoTest, WriteThenReadBack) {
  const std::string path = Path("round_trip.lcmlog");
  const std::vector<Expected> expected = WriteExampleLog(path);

  LogReader reader;
  std::string error;
  ASSERT_TRUE(reader.Open(path, &error)) << error;
  const std::vector<LogEvent> events = ReadAll(&reader);
  ExpectEvents(events, expected, expected.size());
  EXPECT_FALSE(reader.TruncatedTail());
  EXPECT_EQ(reader.tail_offset(), reader.file_size());
  EXPECT_EQ(reader.skipped_bytes(), 0);

  strain_t decoded{};
  ASSERT_EQ(DecodeMessage(events[0].data.data(), events[0].data.size(), &decoded), DecodeError::kNone);
  EXPECT_EQ(decoded.deflection_rad[1], 0.0125);
}

TEST_F(LogIoTest, LcmLogFileReadsOurLog) {
  const std::string path = Path("compat.lcmlog");
  const std::vector<Expected> expected = WriteExampleLog(path);
  lcm::LogFile log(path, "r");
  ASSERT_TRUE(log.good());
  size_t count = 0;
  while (const lcm::LogEvent* event = log.readNextEvent()) {
    ASSERT_LT(count, expected.size());
    EXPECT_EQ(event->channel, expected[count].channel);
    EXPECT_EQ(event->timestamp, expected[count].timestamp_us);
    const auto* data = static_cast<const uint8_t*>(event->data);
    EXPECT_EQ(std::vector<uint8_t>(data, data + event->datalen), expected[count].data);
    ++count;
  }
  EXPECT_EQ(count, expected.size());
}

// Counts what an LCM instance delivers, per channel.
struct Counter {
  void Handle(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
    const auto* data = static_cast<const uint8_t*>(buffer->data);
    received.push_back({channel, buffer->recv_utime, {data, data + buffer->data_size}});
  }
  std::vector<Expected> received;
};

TEST_F(LogIoTest, LcmFileProviderPlaysOurLog) {
  const std::string path = Path("provider.lcmlog");
  const std::vector<Expected> expected = WriteExampleLog(path);
  lcm::LCM lcm("file://" + path + "?speed=0");
  ASSERT_TRUE(lcm.good());
  Counter counter;
  lcm.subscribe(".*", &Counter::Handle, &counter);
  while (lcm.handle() == 0) {
  }
  ASSERT_EQ(counter.received.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    // recv_utime is replay time here, not the logged timestamp.
    EXPECT_EQ(counter.received[i].channel, expected[i].channel);
    EXPECT_EQ(counter.received[i].data, expected[i].data);
  }
}

// lcm-logplayer reads our log and republishes it into a file:// writer: what
// comes out must be the same events.
TEST_F(LogIoTest, LcmLogplayerReplaysOurLog) {
  if (std::system("command -v lcm-logplayer > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "lcm-logplayer not installed";
  }
  const std::string input = Path("player_in.lcmlog");
  const std::string output = Path("player_out.lcmlog");
  const std::vector<Expected> expected = WriteExampleLog(input);
  const std::string command =
      "lcm-logplayer --speed=1000 --lcm-url='file://" + output + "?mode=w' '" + input + "' > /dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;

  LogReader reader;
  std::string error;
  ASSERT_TRUE(reader.Open(output, &error)) << error;
  const std::vector<LogEvent> events = ReadAll(&reader);
  ASSERT_EQ(events.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(events[i].channel, expected[i].channel);
    EXPECT_EQ(events[i].data, expected[i].data);
  }
}

TEST_F(LogIoTest, LogCutMidEventKeepsTheCompleteEvents) {
  const std::string path = Path("full.lcmlog");
  const std::vector<Expected> expected = WriteExampleLog(path);
  const std::vector<uint8_t> bytes = ReadBytes(path);

  // Offsets where each event ends, from a reading of the intact log.
  const std::vector<int64_t> event_ends = EventEnds(path);
  ASSERT_EQ(event_ends.size(), expected.size());
  ASSERT_EQ(event_ends.back(), static_cast<int64_t>(bytes.size()));

  // Cut anywhere in the last three events, sync word and header included.
  const int64_t first_cut = event_ends[event_ends.size() - 4] + 1;
  for (int64_t cut = first_cut; cut < static_cast<int64_t>(bytes.size()); ++cut) {
    const std::string cut_path = Path("cut.lcmlog");
    WriteBytes(cut_path, std::vector<uint8_t>(bytes.begin(), bytes.begin() + cut));
    size_t complete = 0;
    while (complete < event_ends.size() && event_ends[complete] <= cut) ++complete;

    LogReader reader;
    std::string error;
    ASSERT_TRUE(reader.Open(cut_path, &error));
    const std::vector<LogEvent> events = ReadAll(&reader);
    ExpectEvents(events, expected, complete);
    // A cut on an event boundary leaves a shorter but intact log.
    const bool on_boundary = event_ends[complete - 1] == cut;
    EXPECT_EQ(reader.TruncatedTail(), !on_boundary) << "cut at " << cut;
    EXPECT_EQ(reader.tail_offset(), event_ends[complete - 1]) << "cut at " << cut;
    EXPECT_EQ(reader.file_size(), cut);
  }
}

TEST_F(LogIoTest, LeadingGarbageIsNotALog) {
  const std::string path = Path("garbage.lcmlog");
  WriteExampleLog(path);
  std::vector<uint8_t> bytes = ReadBytes(path);
  bytes.insert(bytes.begin(), {0x00, 0x11, 0xED, 0xA1, 0x42});
  WriteBytes(path, bytes);

  LogReader reader;
  std::string error;
  EXPECT_FALSE(reader.Open(path, &error));
  EXPECT_NE(error.find("not an LCM log"), std::string::npos) << error;
}

TEST_F(LogIoTest, GarbageBetweenEventsIsSkippedAndCounted) {
  const std::string path = Path("garbage_mid.lcmlog");
  const std::vector<Expected> expected = WriteExampleLog(path);
  const std::vector<int64_t> event_ends = EventEnds(path);
  std::vector<uint8_t> bytes = ReadBytes(path);
  // After event 4: 5 bytes that are not an event (one starts like a sync word).
  bytes.insert(bytes.begin() + event_ends[4], {0x00, 0x11, 0xED, 0xA1, 0x42});
  WriteBytes(path, bytes);

  LogReader reader;
  std::string error;
  ASSERT_TRUE(reader.Open(path, &error)) << error;
  const std::vector<LogEvent> events = ReadAll(&reader);
  // Event 4 is dropped too: no sync word follows it, so its length cannot be trusted.
  ASSERT_EQ(events.size(), expected.size() - 1);
  EXPECT_EQ(events[4].event_number, 5);
  EXPECT_EQ(reader.corrupt_events(), 1);
  EXPECT_GT(reader.skipped_bytes(), 5);
  EXPECT_FALSE(reader.TruncatedTail());
}

// Issue 16 item 2: a 138-byte log whose one event declares 0x7fffffff data
// bytes made LCM's reader fread into a NULL buffer (exit 139).
TEST_F(LogIoTest, DataLengthBeyondTheFileIsRejectedBeforeAllocating) {
  const std::string path = Path("huge_datalen.lcmlog");
  WriteBytes(path, HugeDataLengthLog());

  LogReader reader;
  std::string error;
  ASSERT_TRUE(reader.Open(path, &error)) << error;
  LogEvent event;
  EXPECT_FALSE(reader.Next(&event));
  EXPECT_EQ(reader.events_read(), 0);
  EXPECT_EQ(reader.corrupt_events(), 1);
  EXPECT_TRUE(reader.TruncatedTail());
  EXPECT_EQ(reader.tail_offset(), 0);
  EXPECT_EQ(reader.file_size(), 138);
}

// Issue 16 item 8: a zero-length channel name mid-log stopped replay.
TEST_F(LogIoTest, ZeroLengthChannelMidLogIsSkippedAndTheRestRead) {
  const std::string path = Path("zero_channel.lcmlog");
  const std::vector<Expected> expected = WriteExampleLog(path);
  const std::vector<int64_t> event_ends = EventEnds(path);
  std::vector<uint8_t> bytes = ReadBytes(path);
  const std::vector<uint8_t> bad = LogEventHeader(99, 5, 0, 4);
  bytes.insert(bytes.begin() + event_ends[9], bad.begin(), bad.end());
  bytes.insert(bytes.begin() + event_ends[9] + static_cast<int64_t>(bad.size()), {1, 2, 3, 4});
  WriteBytes(path, bytes);

  LogReader reader;
  std::string error;
  ASSERT_TRUE(reader.Open(path, &error));
  const std::vector<LogEvent> events = ReadAll(&reader);
  ASSERT_EQ(events.size(), expected.size());
  ExpectEvents(events, expected, expected.size());
  EXPECT_EQ(reader.corrupt_events(), 1);
  EXPECT_EQ(reader.skipped_bytes(), static_cast<int64_t>(bad.size()) + 4);
}

TEST_F(LogIoTest, SpecialFilesAreRefused) {
  for (const std::string path : {"/dev/zero", "/dev/null", "/"}) {
    LogReader reader;
    std::string error;
    EXPECT_FALSE(reader.Open(path, &error)) << path;
    EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;
  }
  const std::string fifo = Path("fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  LogReader reader;
  std::string error;
  EXPECT_FALSE(reader.Open(fifo, &error));  // and does not block waiting for a writer
  EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;
}

// A 2 GB sparse file: one valid event, then a 2 GB hole. The reader jumps
// over the hole (SEEK_DATA) instead of reading 2 GB of zeros.
TEST_F(LogIoTest, SparseHoleAfterAnEventEndsTheLogQuickly) {
  const std::string path = Path("sparse.lcmlog");
  const std::vector<Expected> expected = WriteExampleLog(path);
  const int64_t intact = static_cast<int64_t>(ReadBytes(path).size());
  ASSERT_EQ(truncate(path.c_str(), int64_t{2} << 30), 0);
  LogReader reader;
  std::string error;
  ASSERT_TRUE(reader.Open(path, &error)) << error;
  const std::vector<LogEvent> events = ReadAll(&reader);
  EXPECT_EQ(events.size(), expected.size() - 1);  // the last event has zeros, not a sync word, after it
  EXPECT_TRUE(reader.TruncatedTail());
  EXPECT_LT(reader.tail_offset(), intact);
  EXPECT_EQ(reader.file_size(), int64_t{2} << 30);
  // A sparse file of zeros only is not a log at all.
  const std::string zeros = Path("zeros.lcmlog");
  WriteBytes(zeros, {});
  ASSERT_EQ(truncate(zeros.c_str(), int64_t{2} << 30), 0);
  LogReader zero_reader;
  EXPECT_FALSE(zero_reader.Open(zeros, &error));
  EXPECT_NE(error.find("not an LCM log"), std::string::npos) << error;
}

TEST_F(LogIoTest, CorruptEventInTheMiddleIsReported) {
  const std::string path = Path("corrupt.lcmlog");
  const std::vector<Expected> expected = WriteExampleLog(path);
  const std::vector<int64_t> event_ends = EventEnds(path);
  std::vector<uint8_t> bytes = ReadBytes(path);
  const size_t corrupt = 10;
  bytes[static_cast<size_t>(event_ends[corrupt - 1])] = 0;  // sync word of event 10
  WriteBytes(path, bytes);

  LogReader reader;
  std::string error;
  ASSERT_TRUE(reader.Open(path, &error));
  const std::vector<LogEvent> events = ReadAll(&reader);
  // LCM 1.3 drops the event before the damage too (it checks that a sync
  // word follows each event); the intact events before that come out and
  // the damage is reported, as a tail or as skipped bytes.
  ASSERT_GE(events.size(), corrupt - 1);
  ExpectEvents({events.begin(), events.begin() + corrupt - 1}, expected, corrupt - 1);
  EXPECT_TRUE(reader.TruncatedTail() || reader.skipped_bytes() > 0);
  if (reader.TruncatedTail()) {
    EXPECT_EQ(reader.tail_offset(), event_ends[events.size() - 1]);
  }
}

TEST_F(LogIoTest, EmptyLogHasNoEventsAndNoTail) {
  const std::string path = Path("empty.lcmlog");
  LogWriter writer;
  std::string error;
  ASSERT_TRUE(writer.Open(path, &error)) << error;
  ASSERT_TRUE(writer.Close());
  LogReader reader;
  ASSERT_TRUE(reader.Open(path, &error)) << error;
  LogEvent event;
  EXPECT_FALSE(reader.Next(&event));
  EXPECT_FALSE(reader.TruncatedTail());
  EXPECT_EQ(reader.file_size(), 0);
}

TEST_F(LogIoTest, RejectsBadChannelsAndClosedWriter) {
  LogWriter writer;
  const uint8_t byte = 0;
  EXPECT_FALSE(writer.Write("STRAIN", 0, &byte, 1));  // not open
  std::string error;
  ASSERT_TRUE(writer.Open(Path("bad.lcmlog"), &error)) << error;
  EXPECT_FALSE(writer.Write("", 0, &byte, 1));
  EXPECT_FALSE(writer.Write(std::string(64, 'C'), 0, &byte, 1));
  EXPECT_TRUE(writer.Write(std::string(63, 'C'), 0, &byte, 1));
  EXPECT_TRUE(writer.Write("EMPTY", 0, nullptr, 0));
  EXPECT_EQ(writer.events_written(), 2);
}

TEST_F(LogIoTest, OpenFailuresExplain) {
  std::string error;
  LogWriter writer;
  EXPECT_FALSE(writer.Open(Path("missing_dir/out.lcmlog"), &error));
  EXPECT_NE(error.find("missing_dir/out.lcmlog"), std::string::npos) << error;
  LogReader reader;
  error.clear();
  EXPECT_FALSE(reader.Open(Path("missing.lcmlog"), &error));
  EXPECT_NE(error.find("missing.lcmlog"), std::string::npos) << error;
}

}  // namespace
}  // namespace birotor
