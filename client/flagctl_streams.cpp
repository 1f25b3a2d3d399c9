// The subcommands that read a server's streams: watch (a line a second), record (every channel
// into an LCM log) and snapshot (a whole frame into a picture file).
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <memory>
#include <optional>

#include "common/cli_checks.hpp"
#include "client/flagctl_commands.hpp"
#include "client/flagctl_link.hpp"
#include "client/frame_output.hpp"
#include "client/log_recorder.hpp"
#include "common/picture_file.hpp"
#include "client/printing.hpp"
#include "client/tile_assembler.hpp"
#include "flagsim/frame_t.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "flagsim/state_t.hpp"
#include "flagsim/status_t.hpp"
#include "flagsim/tile_t.hpp"

namespace flagsim {
namespace {

/// Prints one line a second about the STATE stream until `duration` (0: until interrupted).
int Watch(const Globals& globals, double duration, const std::atomic<bool>& stop) {
  Link link(globals);
  std::optional<state_t> latest;
  int64_t states = 0, state_bytes = 0, total_states = 0, invalid = 0;
  std::optional<status_t> status;
  SubscribeDecoded<state_t>(
      link.bus, link.channels.state,
      [&](const state_t& state) {
        latest = state;
        ++states;
        ++total_states;
        state_bytes += state.getEncodedSize();
      },
      &invalid, 1000);
  SubscribeDecoded<status_t>(
      link.bus, link.channels.status, [&status](const status_t& s) { status = s; }, &invalid);
  int64_t frames = 0, tiles = 0, tile_bytes = 0;
  SubscribeDecoded<frame_t>(
      link.bus, link.channels.frame, [&frames](const frame_t&) { ++frames; }, &invalid, 1000);
  SubscribeDecoded<tile_t>(
      link.bus, link.channels.tile,
      [&](const tile_t& tile) {
        ++tiles;
        tile_bytes += tile.num_bytes;
      },
      &invalid, 10000);
  const double start = MonotonicSeconds();
  double last_line = start;
  while (!stop.load()) {
    const double now = MonotonicSeconds();
    if (duration > 0 && now - start >= duration) break;
    if (total_states == 0 && now - start >= globals.timeout && duration == 0) break;
    link.bus.Handle(50);
    if (MonotonicSeconds() - last_line < 1.0 || !latest) continue;
    const double elapsed = MonotonicSeconds() - last_line;
    std::printf("t %9.3f s  step %8lld  STATE %5.1f Hz %6.1f KB  hash %016llx  tip %s  kinetic %.4g J",
                latest->sim_time, static_cast<long long>(latest->step), states / elapsed,
                states > 0 ? state_bytes / 1024.0 / states : 0.0,
                static_cast<unsigned long long>(latest->state_hash), TipText(*latest).c_str(),
                latest->kinetic_energy);
    if (status) std::printf("  rtf %.2f  step %.0f us", status->real_time_factor, status->step_time_us);
    if (frames > 0) {
      std::printf("  FRAME %4.1f Hz %5.1f tiles/frame %7.1f KB/s", frames / elapsed, double(tiles) / frames,
                  tile_bytes / 1024.0 / elapsed);
    }
    std::printf("\n");
    std::fflush(stdout);
    states = state_bytes = frames = tiles = tile_bytes = 0;
    last_line = MonotonicSeconds();
  }
  if (invalid > 0)
    std::fprintf(stderr, "flagctl: %lld undecodable message(s) ignored\n", static_cast<long long>(invalid));
  if (total_states == 0) return link.NoAnswer("STATE");
  std::printf("%lld states received\n", static_cast<long long>(total_states));
  return kOk;
}

/// Asks for a keyframe, assembles the tiles, checks the frame hash, writes a PNG or a JPEG as the
/// file's name says (picture_file.hpp). Once the request is answered, the frames that count are
/// the keyframe naming it and any drawn from a later step than the one it was taken at: frames
/// still in the server's pipeline when it came may show the picture before the commands that
/// preceded it (a camera size, say). If no answer comes within kRefreshAnswerWait (nobody takes
/// commands: lcm-logplayer playing a log, say), any whole frame of the stream counts, and the
/// request is sent again now and then in case a server is there after all.
int Snapshot(const Globals& globals, const std::string& path) {
  std::string problem;
  const std::optional<PictureFormat> format = PictureFormatOf(path, &problem);
  if (!format) {  // before anything is asked of the server
    std::fprintf(stderr, "flagctl snapshot: -o %s\n", problem.c_str());
    return kUsage;
  }
  problem = CheckOutputFile(path);  // as export does: a picture that cannot be written asks nothing
  if (!problem.empty()) {
    std::fprintf(stderr, "flagctl snapshot: %s\n", problem.c_str());
    return kFailed;
  }
  Link link(globals);
  CommandClient client(link.bus, link.channels, std::min(globals.timeout, kRefreshAnswerWait), link.signer);
  TileAssembler assembler;
  bool counting = false;  // frames count: after our request was answered, or with nobody answering
  bool answered = false;
  int64_t answered_step = -1;                           // the step our first answered request was taken at
  const int64_t first_request = client.last_sequence() + 1;  // our requests' ids: first_request onwards
  bool complete = false, keyframe_incomplete = false;
  // The whole frame is the assembler's image once complete: the bus is not handled after that.
  int64_t frame_id = -1;
  double completed = 0;  // s, monotonic: when the whole frame was there (before the PNG is written)
  int64_t invalid = 0;   // undecodable TILE and FRAME messages: ignored, and said
  SubscribeDecoded<tile_t>(
      link.bus, link.channels.tile, [&](const tile_t& tile) { assembler.AddTile(tile); }, &invalid, 10000);
  SubscribeDecoded<frame_t>(
      link.bus, link.channels.frame,
      [&](const frame_t& manifest) {
        const bool whole = assembler.AddManifest(manifest) == TileAssembler::FrameResult::kComplete;
        if (!counting || complete) return;
        const bool ours = manifest.request_id >= first_request && manifest.request_id <= client.last_sequence();
        if (answered && !ours && manifest.step <= answered_step) return;  // from before the request
        if (whole) {
          frame_id = manifest.frame_id;
          completed = MonotonicSeconds();
        }
        complete = whole;
        keyframe_incomplete |= manifest.keyframe && !whole;
      },
      &invalid, 1000);
  const double start = MonotonicSeconds(), deadline = start + globals.timeout;
  while (!complete && MonotonicSeconds() < deadline) {
    // A keyframe that arrived with tiles missing calls for another request (a new id).
    keyframe_incomplete = false;
    const CommandOutcome outcome = client.Send(link.channels.refresh, refresh_request_t{});
    if (outcome.result == CommandOutcome::kRejected) return Report(link, outcome);
    if (outcome.result == CommandOutcome::kAccepted && !answered) {
      answered = true;
      answered_step = outcome.step;
    }
    counting = true;
    const double wait =
        std::min(deadline - MonotonicSeconds(), answered ? globals.timeout : kRefreshAnswerWait);
    HandleUntil(link.bus, wait, [&] { return complete || keyframe_incomplete; });
  }
  if (invalid > 0) {
    std::fprintf(stderr, "flagctl snapshot: %lld undecodable TILE or FRAME message(s) ignored\n",
                 static_cast<long long>(invalid));
  }
  if (!complete) return link.NoAnswer("complete frame");
  const int width = assembler.width(), height = assembler.height();
  problem = WritePicture(path, *format, width, height, assembler.image().data());
  if (!problem.empty()) {
    std::fprintf(stderr, "flagctl: %s\n", problem.c_str());
    return kFailed;
  }
  std::printf("%s: %d x %d, frame %lld, complete %.0f ms after the request%s\n", path.c_str(), width, height,
              static_cast<long long>(frame_id), 1000 * (completed - start),
              answered
                  ? ""
                  : " (no server answered it: a stream that takes no commands, such as a log playing back)");
  return kOk;
}

/// Records every channel with the prefix to an LCM log until `duration` or an interrupt.
int Record(const Globals& globals, const std::string& path, double duration, const std::atomic<bool>& stop) {
  Link link(globals);
  std::unique_ptr<LogRecorder> recorder;
  try {
    recorder = std::make_unique<LogRecorder>(link.bus, link.channels, path);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "flagctl: %s\n", error.what());
    return kFailed;  // a file that cannot be written
  }
  const double start = MonotonicSeconds();
  // A keyframe request first, and again while no checkpoint has come (LogRecorder): the server
  // answers with a CHECKPOINT and a full frame, so the log replays (flagd replay) and exports
  // (flagctl export) from its beginning. Recorded meanwhile; nobody may answer (a log playing
  // back), and the recording goes on regardless.
  CommandClient refresh(link.bus, link.channels, std::min(globals.timeout, 1.0), link.signer);
  while (!stop.load() && !recorder->failed()) {
    const double now = MonotonicSeconds();
    if (duration > 0 && now - start >= duration) break;
    if (recorder->events() == 0 && now - start >= globals.timeout && duration == 0) break;
    if (recorder->KeyframeRequestDue(now)) refresh.Send(link.channels.refresh, refresh_request_t{});
    link.bus.Handle(50);
  }
  if (recorder->failed()) {  // the disk is full: the log ends at its last whole event
    std::fprintf(stderr, "flagctl: recording stopped after %.1f s: %s\n", MonotonicSeconds() - start,
                 recorder->error().c_str());
    return kFailed;
  }
  std::printf("%s: %lld events, %.1f KB in %.1f s\n", path.c_str(),
              static_cast<long long>(recorder->events()), recorder->bytes() / 1024.0,
              MonotonicSeconds() - start);
  return recorder->events() > 0 ? kOk : link.NoAnswer("message");
}

}  // namespace

void AddWatchCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* watch = app.add_subcommand("watch", "print the state stream, a line a second");
  auto duration = std::make_shared<double>(0);
  watch->add_option("--duration", *duration, "seconds to watch (0: until interrupted)")->check(ZeroOrMore());
  invocation.RunOnParse(
      watch, [&invocation, duration] { return Watch(invocation.globals, *duration, invocation.stop); });
}

void AddRecordCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* record = app.add_subcommand("record", "record every channel of the server to an LCM log");
  auto path = std::make_shared<std::string>();
  auto duration = std::make_shared<double>(0);
  record->add_option("-o,--output", *path, "the log file to write")->required();
  record->add_option("--duration", *duration, "seconds to record (0: until interrupted)")
      ->check(ZeroOrMore());
  invocation.RunOnParse(record, [&invocation, path, duration] {
    return Record(invocation.globals, *path, *duration, invocation.stop);
  });
}

void AddSnapshotCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* snapshot = app.add_subcommand("snapshot", "ask for a full frame and write it as a PNG or a JPEG");
  auto path = std::make_shared<std::string>();
  snapshot->add_option("-o,--output", *path, "the file to write: NAME.png, or NAME.jpg (NAME.jpeg) for JPEG")
      ->required();
  invocation.RunOnParse(snapshot, [&invocation, path] { return Snapshot(invocation.globals, *path); });
}

}  // namespace flagsim
