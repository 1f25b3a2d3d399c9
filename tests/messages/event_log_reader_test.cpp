#include "messages/event_log_reader.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <lcm/lcm-cpp.hpp>
#include <random>
#include <string>
#include <vector>

namespace flagsim {
namespace {

/// A file in the test's temporary directory, removed afterwards.
class TempFile {
 public:
  explicit TempFile(const std::string& name)
      : path_(std::string(::testing::TempDir()) + "/" + std::to_string(getpid()) + "_" + name) {}
  ~TempFile() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

struct Written {
  std::string channel;
  std::vector<uint8_t> data;
  int64_t timestamp;
};

/// Events of varied sizes (an empty one among them), as lcm::LogFile writes them.
std::vector<Written> SomeEvents() {
  std::vector<Written> events;
  for (int i = 0; i < 5; ++i) {
    Written event{"FLAGSIM_" + std::string(size_t(i + 1), char('A' + i)), {}, 1000000 + 250 * i};
    for (int k = 0; k < 37 * i; ++k) event.data.push_back(uint8_t(k * 7 + i));
    events.push_back(event);
  }
  return events;
}

void WriteWithLcm(const std::string& path, const std::vector<Written>& events) {
  lcm::LogFile log(path, "w");
  ASSERT_TRUE(log.good());
  for (const Written& written : events) {
    lcm::LogEvent event;
    event.timestamp = written.timestamp;
    event.channel = written.channel;
    event.datalen = static_cast<int32_t>(written.data.size());
    event.data = const_cast<uint8_t*>(written.data.data());
    ASSERT_EQ(log.writeEvent(&event), 0);
  }
}

std::vector<uint8_t> ReadBytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(file), {});
}

void WriteBytes(const std::string& path, const std::vector<uint8_t>& bytes, size_t count) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(count));
}

/// Every event the reader gives until it stops.
std::vector<LogEvent> ReadAll(EventLogReader* reader) {
  std::vector<LogEvent> events;
  LogEvent event;
  while (reader->Next(&event)) events.push_back(event);
  return events;
}

/// Bytes an event takes in the file.
size_t EventBytes(const Written& event) {
  return EventLogReader::kHeaderBytes + event.channel.size() + event.data.size();
}

TEST(EventLogReader, ReadsWhatLcmWrote) {
  TempFile file("whole.lcmlog");
  const std::vector<Written> written = SomeEvents();
  WriteWithLcm(file.path(), written);
  EventLogReader reader(file.path());
  const std::vector<LogEvent> events = ReadAll(&reader);
  ASSERT_EQ(events.size(), written.size());
  size_t offset = 0;
  for (size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(events[i].number, int64_t(i));
    EXPECT_EQ(events[i].timestamp, written[i].timestamp);
    EXPECT_EQ(events[i].channel, written[i].channel);
    EXPECT_EQ(events[i].data, written[i].data);
    EXPECT_EQ(events[i].offset, offset);
    offset += EventBytes(written[i]);
  }
  EXPECT_EQ(reader.end(), EventLogReader::End::kClean);
  EXPECT_EQ(reader.problem(), "");
  EXPECT_EQ(reader.offset(), reader.size());
  EXPECT_FALSE(reader.Next(nullptr)) << "and it stays ended";
}

TEST(EventLogReader, SkipsTheDataOfChannelsNotWanted) {
  TempFile file("skip.lcmlog");
  const std::vector<Written> written = SomeEvents();
  WriteWithLcm(file.path(), written);
  EventLogReader reader(file.path());
  LogEvent event;
  size_t count = 0;
  while (reader.Next(&event, [](const std::string& channel) { return channel == "FLAGSIM_CCC"; })) {
    EXPECT_EQ(event.channel, written[count].channel);
    EXPECT_EQ(event.data, event.channel == "FLAGSIM_CCC" ? written[count].data : std::vector<uint8_t>{});
    ++count;
  }
  EXPECT_EQ(count, written.size());
  EXPECT_EQ(reader.end(), EventLogReader::End::kClean);
}

// A recorder killed mid-write leaves its last event cut anywhere: in the header or the body.
TEST(EventLogReader, ALogCutAnywhereInItsLastEventGivesEveryWholeEventBefore) {
  TempFile whole("whole.lcmlog"), cut("cut.lcmlog");
  const std::vector<Written> written = SomeEvents();
  WriteWithLcm(whole.path(), written);
  const std::vector<uint8_t> bytes = ReadBytes(whole.path());
  const size_t last_start = bytes.size() - EventBytes(written.back());
  for (size_t length = last_start + 1; length < bytes.size(); ++length) {
    WriteBytes(cut.path(), bytes, length);
    EventLogReader reader(cut.path());
    const std::vector<LogEvent> events = ReadAll(&reader);
    ASSERT_EQ(events.size(), written.size() - 1) << "cut at " << length;
    EXPECT_EQ(events.back().data, written[written.size() - 2].data);
    EXPECT_EQ(reader.end(), EventLogReader::End::kTruncated) << "cut at " << length;
    EXPECT_EQ(reader.offset(), last_start);
    const std::string where = cut.path() + ": at byte " + std::to_string(last_start) + ", event " +
                              std::to_string(written.size() - 1) + ": cut short";
    EXPECT_EQ(reader.problem().rfind(where, 0), 0u) << reader.problem();
  }
  WriteBytes(cut.path(), bytes, last_start);  // cut between two events: a whole, shorter log
  EventLogReader reader(cut.path());
  EXPECT_EQ(ReadAll(&reader).size(), written.size() - 1);
  EXPECT_EQ(reader.end(), EventLogReader::End::kClean);
}

TEST(EventLogReader, SaysHowMuchOfTheCutEventIsThere) {
  TempFile whole("whole.lcmlog"), cut("cut.lcmlog");
  const std::vector<Written> written = SomeEvents();
  WriteWithLcm(whole.path(), written);
  const std::vector<uint8_t> bytes = ReadBytes(whole.path());
  const size_t last_bytes = EventBytes(written.back());
  const size_t last_start = bytes.size() - last_bytes;
  WriteBytes(cut.path(), bytes, last_start + 10);
  EventLogReader in_header(cut.path());
  ReadAll(&in_header);
  EXPECT_NE(in_header.problem().find("inside its header (10 of 28 bytes are there)"), std::string::npos)
      << in_header.problem();
  WriteBytes(cut.path(), bytes, last_start + 40);
  EventLogReader in_body(cut.path());
  ReadAll(&in_body);
  EXPECT_NE(in_body.problem().find("(40 of its " + std::to_string(last_bytes) + " bytes are there)"),
            std::string::npos)
      << in_body.problem();
}

TEST(EventLogReader, AnEmptyFileIsAnEmptyLog) {
  TempFile file("empty.lcmlog");
  WriteBytes(file.path(), {}, 0);
  EventLogReader reader(file.path());
  EXPECT_TRUE(ReadAll(&reader).empty());
  EXPECT_EQ(reader.end(), EventLogReader::End::kClean);
}

TEST(EventLogReader, AMissingFileOrADirectoryIsNamed) {
  try {
    EventLogReader reader("/nonexistent/run.lcmlog");
    FAIL() << "no exception";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/run.lcmlog"), std::string::npos);
  }
  EXPECT_THROW(EventLogReader{::testing::TempDir()}, std::runtime_error);  // braces: not a declaration
}

TEST(EventLogReader, AFileThatIsNotALogSaysSo) {
  TempFile file("text.lcmlog");
  const std::string text = "garbage\n";
  WriteBytes(file.path(), std::vector<uint8_t>(text.begin(), text.end()), text.size());
  EventLogReader reader(file.path());
  EXPECT_TRUE(ReadAll(&reader).empty());
  EXPECT_EQ(reader.end(), EventLogReader::End::kCorrupt);
  EXPECT_NE(reader.problem().find("not an LCM event log"), std::string::npos) << reader.problem();
}

/// The log with event `index`'s 4-byte big-endian field at `field_offset` set to `value`.
std::vector<uint8_t> WithField(std::vector<uint8_t> bytes, size_t event_start, size_t field_offset,
                               uint32_t value) {
  for (int i = 0; i < 4; ++i) bytes[event_start + field_offset + i] = uint8_t(value >> (24 - 8 * i));
  return bytes;
}

// Headers that lie stop the reader before it allocates or reads anything they claim; LCM
// 1.3.1's own reader crashes on a data length of 2^31 - 1.
TEST(EventLogReader, LyingHeadersStopItAfterTheEventsBefore) {
  TempFile whole("whole.lcmlog"), bad("bad.lcmlog");
  const std::vector<Written> written = SomeEvents();
  WriteWithLcm(whole.path(), written);
  const std::vector<uint8_t> bytes = ReadBytes(whole.path());
  const size_t third = EventBytes(written[0]) + EventBytes(written[1]);
  struct Case {
    size_t field;  // 0: sync word, 20: channel length, 24: data length
    uint32_t value;
    EventLogReader::End end;
    const char* says;
  };
  const Case cases[] = {
      {0, 0xEDA1DA02, EventLogReader::End::kCorrupt, "no sync word (0xEDA1DA02"},
      {20, 0, EventLogReader::End::kCorrupt, "channel length 0"},
      {20, 0xFFFFFFFF, EventLogReader::End::kCorrupt, "channel length -1"},
      {20, 5000, EventLogReader::End::kCorrupt, "channel length 5000"},
      {24, 0x80000000, EventLogReader::End::kCorrupt, "data length -2147483648"},
      {24, 0x7FFFFFFF, EventLogReader::End::kCorrupt, "data length 2147483647"},
      {24, 1 << 20, EventLogReader::End::kTruncated, "cut short"},  // more than the file holds
  };
  for (const Case& c : cases) {
    WriteBytes(bad.path(), WithField(bytes, third, c.field, c.value), bytes.size());
    EventLogReader reader(bad.path());
    EXPECT_EQ(ReadAll(&reader).size(), 2u) << c.says;
    EXPECT_EQ(reader.end(), c.end) << c.says;
    EXPECT_NE(reader.problem().find(c.says), std::string::npos) << reader.problem();
    EXPECT_NE(reader.problem().find("at byte " + std::to_string(third) + ", event 2"), std::string::npos)
        << reader.problem();
  }
}

TEST(EventLogReader, RandomBytesNeverCrashIt) {
  TempFile whole("whole.lcmlog"), bad("random.lcmlog");
  WriteWithLcm(whole.path(), SomeEvents());
  const std::vector<uint8_t> log = ReadBytes(whole.path());
  std::mt19937 random(11);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<uint8_t> bytes = log;
    if (trial % 3 == 0) {  // pure noise
      bytes.resize(random() % 400);
      for (uint8_t& byte : bytes) byte = uint8_t(random());
    } else {  // a real log with bytes flipped
      for (int flips = 0; flips < 1 + trial % 5; ++flips)
        bytes[random() % bytes.size()] ^= uint8_t(1 + random() % 255);
    }
    WriteBytes(bad.path(), bytes, bytes.size());
    EventLogReader reader(bad.path());
    const std::vector<LogEvent> events = ReadAll(&reader);
    EXPECT_NE(reader.end(), EventLogReader::End::kNotYet);
    EXPECT_LE(reader.offset(), bytes.size());
    EXPECT_EQ(reader.end() == EventLogReader::End::kClean, reader.problem().empty());
    for (const LogEvent& event : events) EXPECT_LE(event.data.size(), bytes.size());
  }
}

}  // namespace
}  // namespace flagsim
