// What a recorder's crash safety costs: a recorded stream written again at its own pace (each
// event when its time stamp falls due, as a recorder receives it) by three writers in turn:
//
//   stdio       lcm::LogFile, LCM's own writer (what the recorders used before): events gather in
//               a stdio buffer, reach the kernel a buffer at a time, never synced
//   whole       EventLogWriter, its sync put off past the run: each event to the kernel whole,
//               in one writev, as it is written
//   whole+sync  EventLogWriter as the recorders use it: the same, and fdatasync once a second
//               on its own thread
//
//   build/bench/log_write_bench LOG [--dir DIR] [--seconds S] [--rounds N]
//
// LOG: a stream to write again, e.g. `flagd render --duration 30 -o stream.lcmlog` (the channels
// a live server publishes, stamped on simulated time: real time's pace) or a `flagctl record`.
// DIR: where the file goes (the disk under test; default "."). The writers take turns, N rounds.
// Per writer: the time each Write call took (median, 99th percentile, largest), the process's
// CPU time over the run's wall time (the syncing thread included), the syncs and their mean
// duration, and the time the last sync took at Close.
#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "messages/event_log_reader.hpp"
#include "messages/event_log_writer.hpp"

namespace {

using Clock = std::chrono::steady_clock;

/// The stream: events with their time stamps, us from the first.
std::vector<flagsim::LogEvent> ReadStream(const std::string& path, double seconds) {
  flagsim::EventLogReader reader(path);
  std::vector<flagsim::LogEvent> events;
  flagsim::LogEvent event;
  int64_t first = -1;
  while (reader.Next(&event)) {
    if (first < 0) first = event.timestamp;
    event.timestamp -= first;
    if (event.timestamp > seconds * 1e6) break;
    events.push_back(event);
  }
  return events;
}

double CpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
         1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

/// How one writer fared over one run.
struct Run {
  std::vector<double> write_us;  ///< each Write call
  double cpu = 0;                ///< CPU seconds over wall seconds of the run
  int64_t syncs = 0;
  double sync_ms = 0;   ///< mean fdatasync
  double close_ms = 0;  ///< Close, with its last sync
};

/// A writer under test: write one event; close.
struct Writer {
  std::function<void(const flagsim::LogEvent&)> write;
  std::function<void()> close;
  std::function<void(Run*)> tally = [](Run*) {};
};

Writer Stdio(const std::string& path) {
  auto log = std::make_shared<lcm::LogFile>(path, "w");
  return {[log](const flagsim::LogEvent& event) {
            lcm::LogEvent copy;
            copy.timestamp = event.timestamp;
            copy.channel = event.channel;
            copy.datalen = int32_t(event.data.size());
            copy.data = const_cast<uint8_t*>(event.data.data());
            log->writeEvent(&copy);
          },
          [log] { std::fflush(log->getFilePtr()); }};
}

Writer Whole(const std::string& path, double sync_interval) {
  auto log = std::make_shared<flagsim::EventLogWriter>(path, sync_interval);
  return {[log](const flagsim::LogEvent& event) {
            log->Write(event.timestamp, event.channel, event.data.data(), event.data.size());
          },
          [log] { log->Close(); },
          [log](Run* run) {
            run->syncs = log->syncs();
            run->sync_ms = log->syncs() > 0 ? 1e3 * log->sync_seconds() / log->syncs() : 0;
          }};
}

// Each event when it falls due on the stream's clock; each Write timed.
Run WriteAtPace(const std::vector<flagsim::LogEvent>& events, Writer writer) {
  Run run;
  const auto start = Clock::now();
  const double cpu_start = CpuSeconds();
  for (const flagsim::LogEvent& event : events) {
    std::this_thread::sleep_until(start + std::chrono::microseconds(event.timestamp));
    const auto before = Clock::now();
    writer.write(event);
    run.write_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - before).count());
  }
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  run.cpu = (CpuSeconds() - cpu_start) / wall;
  writer.tally(&run);
  const auto closing = Clock::now();
  writer.close();
  run.close_ms = std::chrono::duration<double, std::milli>(Clock::now() - closing).count();
  std::sort(run.write_us.begin(), run.write_us.end());
  return run;
}

double Quantile(const std::vector<double>& sorted, double q) {
  return sorted.empty() ? 0 : sorted[std::min(sorted.size() - 1, size_t(q * double(sorted.size())))];
}

}  // namespace

int main(int argc, char** argv) {
  std::string stream_path, directory = ".";
  double seconds = 30;
  int rounds = 2;
  CLI::App app{"log_write_bench: the cost of writing a stream whole and syncing it once a second"};
  app.add_option("log", stream_path, "the stream to write again (an LCM log)")->required();
  app.add_option("--dir", directory, "where to write (the disk under test)")->capture_default_str();
  app.add_option("--seconds", seconds, "of the stream to write, per run")->capture_default_str();
  app.add_option("--rounds", rounds, "runs of each writer, taking turns")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  const std::vector<flagsim::LogEvent> events = ReadStream(stream_path, seconds);
  uint64_t bytes = 0;
  for (const flagsim::LogEvent& event : events) bytes += event.data.size() + event.channel.size() + 28;
  const double span = events.empty() ? 0 : events.back().timestamp * 1e-6;
  std::printf("stream: %zu events, %.1f MB over %.1f s (%.2f MB/s, %.0f events/s), written to %s\n",
              events.size(), bytes / 1e6, span, bytes / 1e6 / span, events.size() / span, directory.c_str());
  std::printf(
      "| writer | round | write p50 us | write p99 us | write max us | CPU %% | syncs | sync ms (mean) | "
      "close ms |\n");
  std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  const std::string path = directory + "/log_write_bench.lcmlog";
  const std::pair<const char*, std::function<Writer()>> writers[] = {
      {"stdio", [&path] { return Stdio(path); }},
      {"whole", [&path] { return Whole(path, 1e9); }},
      {"whole+sync", [&path] { return Whole(path, flagsim::EventLogWriter::kSyncInterval); }}};
  for (int round = 1; round <= rounds; ++round) {
    for (const auto& [name, make] : writers) {
      const Run run = WriteAtPace(events, make());
      std::printf("| %s | %d | %.1f | %.1f | %.0f | %.2f | %lld | %.2f | %.2f |\n", name, round,
                  Quantile(run.write_us, 0.5), Quantile(run.write_us, 0.99), run.write_us.back(),
                  100 * run.cpu, static_cast<long long>(run.syncs), run.sync_ms, run.close_ms);
      std::fflush(stdout);
      std::remove(path.c_str());
    }
  }
  return 0;
}
