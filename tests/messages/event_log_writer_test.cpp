// The crash-safe log writer: what it writes is lcm-logger's format, a process killed after a
// write leaves that event in the file, a disk that fills (mid-event too) leaves a log of whole
// events and a message that says so, and what is written gets synced.
#include "messages/event_log_writer.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <thread>
#include <vector>

#include "messages/event_log_reader.hpp"

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

std::vector<uint8_t> Data(size_t size, int seed) {
  std::vector<uint8_t> data(size);
  for (size_t k = 0; k < size; ++k) data[k] = uint8_t(k * 13 + seed);
  return data;
}

uint64_t FileSize(const std::string& path) {
  struct stat status {};
  return ::stat(path.c_str(), &status) == 0 ? uint64_t(status.st_size) : 0;
}

/// Every whole event in the log, and how it ended.
std::vector<LogEvent> ReadAll(const std::string& path, EventLogReader::End* end) {
  EventLogReader reader(path);
  std::vector<LogEvent> events;
  LogEvent event;
  while (reader.Next(&event)) events.push_back(event);
  *end = reader.end();
  return events;
}

TEST(EventLogWriter, WritesWhatLcmsOwnReaderReads) {
  TempFile file("lcm.lcmlog");
  {
    EventLogWriter writer(file.path());
    for (int i = 0; i < 4; ++i)
      ASSERT_TRUE(writer.Write(1000 + i, "CHANNEL_" + std::to_string(i), Data(50 * i, i).data(), 50 * i));
    EXPECT_EQ(writer.events(), 4);
    EXPECT_EQ(writer.bytes(), FileSize(file.path()));
    EXPECT_TRUE(writer.Close());
  }
  lcm::LogFile log(file.path(), "r");
  ASSERT_TRUE(log.good());
  for (int i = 0; i < 4; ++i) {
    const lcm::LogEvent* event = log.readNextEvent();
    ASSERT_NE(event, nullptr) << "event " << i;
    EXPECT_EQ(event->eventnum, i);
    EXPECT_EQ(event->timestamp, 1000 + i);
    EXPECT_EQ(event->channel, "CHANNEL_" + std::to_string(i));
    const std::vector<uint8_t> data(static_cast<const uint8_t*>(event->data),
                                    static_cast<const uint8_t*>(event->data) + event->datalen);
    EXPECT_EQ(data, Data(50 * i, i));
  }
  EXPECT_EQ(log.readNextEvent(), nullptr);
}

// A child process writes and is killed before it closes the log: nothing it wrote is lost.
TEST(EventLogWriter, AProcessKilledAfterAWriteLeavesEveryEventWhole) {
  TempFile file("killed.lcmlog");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    EventLogWriter writer(file.path(), 3600);  // no sync before the end: the kernel holds it all
    for (int i = 0; i < 5; ++i) writer.Write(i, "KILLED", Data(1000, i).data(), 1000);
    raise(SIGKILL);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  EventLogReader::End end;
  const std::vector<LogEvent> events = ReadAll(file.path(), &end);
  ASSERT_EQ(events.size(), 5u);
  EXPECT_EQ(events.back().data, Data(1000, 4));
  EXPECT_EQ(end, EventLogReader::End::kClean);
}

TEST(EventLogWriter, AFullDiskEndsTheLogAndSaysSo) {
  EventLogWriter writer("/dev/full");  // opens, and every write fails with ENOSPC
  const std::vector<uint8_t> data = Data(100, 1);
  EXPECT_FALSE(writer.Write(0, "FULL", data.data(), data.size()));
  EXPECT_TRUE(writer.failed());
  EXPECT_NE(writer.error().find("writing /dev/full stopped: the disk is full"), std::string::npos)
      << writer.error();
  EXPECT_NE(writer.error().find("its first 0 events, 0 bytes"), std::string::npos) << writer.error();
  EXPECT_FALSE(writer.Write(1, "FULL", data.data(), data.size())) << "the log stays ended";
  EXPECT_EQ(writer.events(), 0);
  EXPECT_FALSE(writer.Close());
}

// The file size limit (RLIMIT_FSIZE) stops a write part way through an event, as a disk that
// fills does: the part is cut off, and the log reads to its end, clean.
TEST(EventLogWriter, AFileThatFillsMidEventIsCutBackToItsWholeEvents) {
  TempFile file("limit.lcmlog");
  const size_t event_bytes = EventLogReader::kHeaderBytes + 5 + 300;
  rlimit before{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &before), 0);
  void (*const previous)(int) = std::signal(SIGXFSZ, SIG_IGN);  // EFBIG, not a signal that kills
  rlimit limit = before;
  limit.rlim_cur = 3 * event_bytes + 100;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &limit), 0);
  EventLogWriter writer(file.path());
  int written = 0;
  while (written < 10 && writer.Write(written, "LIMIT", Data(300, written).data(), 300)) ++written;
  setrlimit(RLIMIT_FSIZE, &before);
  std::signal(SIGXFSZ, previous);

  EXPECT_EQ(written, 3);
  EXPECT_EQ(writer.events(), 3);
  EXPECT_EQ(writer.bytes(), 3 * event_bytes);
  EXPECT_EQ(FileSize(file.path()), 3 * event_bytes) << "the part of the fourth event is gone";
  EXPECT_NE(writer.error().find("the file reached the largest size allowed"), std::string::npos)
      << writer.error();
  EXPECT_NE(writer.error().find("its first 3 events, " + std::to_string(3 * event_bytes) +
                                " bytes, every one whole"),
            std::string::npos)
      << writer.error();
  EventLogReader::End end;
  const std::vector<LogEvent> events = ReadAll(file.path(), &end);
  EXPECT_EQ(events.size(), 3u);
  EXPECT_EQ(end, EventLogReader::End::kClean);
}

// The syncing thread's own clock: polled for, with a generous bound.
TEST(EventLogWriter, SyncsWhatWasWrittenWithinItsInterval) {
  TempFile file("sync.lcmlog");
  EventLogWriter writer(file.path(), 0.01);
  const auto synced = [&writer](int64_t count) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (writer.syncs() < count && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return writer.syncs() >= count;
  };
  EXPECT_EQ(writer.syncs(), 0) << "nothing written, nothing to sync";
  const std::vector<uint8_t> data = Data(64, 2);
  ASSERT_TRUE(writer.Write(0, "SYNC", data.data(), data.size()));
  EXPECT_TRUE(synced(1));
  ASSERT_TRUE(writer.Write(1, "SYNC", data.data(), data.size()));
  EXPECT_TRUE(synced(2));
  EXPECT_TRUE(writer.Close());
}

TEST(EventLogWriter, AnUnwritablePathIsNamed) {
  try {
    EventLogWriter writer("/nonexistent-dir/run.lcmlog");
    FAIL() << "opened a log in a directory that does not exist";
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()),
              "cannot write the log file /nonexistent-dir/run.lcmlog: No such file or directory");
  }
}

}  // namespace
}  // namespace flagsim
