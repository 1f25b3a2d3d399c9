#include "client/flagctl_commands.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <iostream>
#include <optional>

#include "client/command_client.hpp"
#include "client/log_recorder.hpp"
#include "client/png_file.hpp"
#include "client/printing.hpp"
#include "client/stream_reader.hpp"
#include "client/tile_assembler.hpp"
#include "flagsim/camera_command_t.hpp"
#include "flagsim/frame_t.hpp"
#include "flagsim/param_command_t.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "flagsim/timeline_t.hpp"
#include "flagsim/wind_command_t.hpp"
#include "messages/bus.hpp"
#include "messages/channels.hpp"

namespace flagsim {

std::atomic<bool> g_stop{false};

namespace {

/// The bus and channels one subcommand talks on.
struct Link {
  explicit Link(const Globals& globals)
      : bus(Bus::WithReceiveBuffer(globals.lcm_url, 8 << 20)), channels(globals.prefix), globals(globals) {}
  Bus bus;
  Channels channels;
  const Globals& globals;

  int NoAnswer(const std::string& what) const {
    std::fprintf(stderr, "flagctl: no %s from a server with prefix %s on %s within %g s\n", what.c_str(),
                 channels.prefix.c_str(), bus.url().c_str(), globals.timeout);
    return kNoAnswer;
  }
};

int Report(const Link& link, const CommandOutcome& outcome) {
  if (outcome.other_servers > 0) {
    std::fprintf(stderr,
                 "flagctl: warning: the server that answered (id %016llx) hears %d other server(s) on prefix "
                 "%s: each takes this command too, and their streams interleave\n",
                 static_cast<unsigned long long>(outcome.server_id), outcome.other_servers,
                 link.channels.prefix.c_str());
  }
  switch (outcome.result) {
    case CommandOutcome::kAccepted:
      std::printf("accepted at step %lld\n", static_cast<long long>(outcome.step));
      if (!outcome.reason.empty()) std::printf("note: %s\n", outcome.reason.c_str());
      return kOk;
    case CommandOutcome::kRejected:
      std::fprintf(stderr, "flagctl: rejected: %s\n", outcome.reason.c_str());
      return kRejected;
    case CommandOutcome::kNoAnswer:
      break;
  }
  return link.NoAnswer("answer");
}

}  // namespace

int Wind(const Globals& globals, const std::vector<double>& velocity, double gust, double ramp) {
  Link link(globals);
  CommandClient client(link.bus, link.channels, globals.timeout, globals.signer);
  wind_command_t command{};
  for (int k = 0; k < 3; ++k) command.velocity[k] = velocity[k];
  command.gust = gust;
  command.ramp_time = ramp;
  return Report(link, client.Send(link.channels.wind, command));
}

int Set(const Globals& globals, const std::vector<std::string>& assignments, bool reset) {
  param_command_t command{};
  command.reset_to_scene = reset;
  for (const std::string& assignment : assignments) {
    const size_t equals = assignment.find('=');
    if (equals == std::string::npos || equals == 0) {
      std::fprintf(stderr, "flagctl: '%s' is not NAME=VALUE\n", assignment.c_str());
      return kUsage;
    }
    command.names.push_back(assignment.substr(0, equals));
    command.values.push_back(assignment.substr(equals + 1));
  }
  command.num_assignments = static_cast<int32_t>(command.names.size());
  Link link(globals);
  CommandClient client(link.bus, link.channels, globals.timeout, globals.signer);
  return Report(link, client.Send(link.channels.param, command));
}

int Refresh(const Globals& globals) {
  Link link(globals);
  CommandClient client(link.bus, link.channels, globals.timeout, globals.signer);
  std::optional<state_t> state;
  SubscribeDecoded<state_t>(link.bus, link.channels.state, [&state](const state_t& s) { state = s; });
  const CommandOutcome outcome = client.Send(link.channels.refresh, refresh_request_t{});
  if (outcome.result != CommandOutcome::kAccepted) return Report(link, outcome);
  state.reset();  // the full state published for this request comes after the ACK
  if (!HandleUntil(link.bus, globals.timeout, [&state] { return state.has_value(); })) {
    return link.NoAnswer("STATE");
  }
  std::printf("step %lld  t = %.3f s  %d x %d nodes  state hash %016llx\n",
              static_cast<long long>(state->step), state->sim_time, state->cols, state->rows,
              static_cast<unsigned long long>(state->state_hash));
  return kOk;
}

int Params(const Globals& globals) {
  Link link(globals);
  const auto params = AwaitMessage<params_t>(link.bus, link.channels.params, globals.timeout);
  if (!params) return link.NoAnswer("PARAMS");
  PrintParams(*params, std::cout);
  return kOk;
}

int Status(const Globals& globals) {
  Link link(globals);
  const auto status = AwaitMessage<status_t>(link.bus, link.channels.status, globals.timeout);
  if (!status) return link.NoAnswer("STATUS");
  PrintStatus(*status, std::cout);
  return kOk;
}

/// Prints one line a second about the STATE stream until `duration` (0: until interrupted).
int Watch(const Globals& globals, double duration) {
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
  while (!g_stop.load()) {
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

/// Asks for a keyframe, assembles the tiles, checks the frame hash, writes a PNG. Frames count
/// once the request is answered; if no answer comes within kRefreshAnswerWait (nobody takes
/// commands: lcm-logplayer playing a log, say), any whole frame of the stream counts, and the
/// request is sent again now and then in case a server is there after all.
int Snapshot(const Globals& globals, const std::string& path) {
  constexpr double kRefreshAnswerWait = 1.0;  // s
  Link link(globals);
  CommandClient client(link.bus, link.channels, std::min(globals.timeout, kRefreshAnswerWait), globals.signer);
  TileAssembler assembler;
  bool counting = false;  // frames count: after our request was answered, or with nobody answering
  bool complete = false, keyframe_incomplete = false;
  // The whole frame, copied as it completes: the assembler goes on with later frames.
  std::vector<uint8_t> picture;
  int width = 0, height = 0;
  int64_t frame_id = -1;
  double completed = 0;  // s, monotonic: when the whole frame was there (before the PNG is written)
  SubscribeDecoded<tile_t>(
      link.bus, link.channels.tile, [&](const tile_t& tile) { assembler.AddTile(tile); }, nullptr, 10000);
  SubscribeDecoded<frame_t>(
      link.bus, link.channels.frame,
      [&](const frame_t& manifest) {
        const bool whole = assembler.AddManifest(manifest) == TileAssembler::FrameResult::kComplete;
        if (!counting || complete) return;
        if (whole) {
          picture = assembler.image();
          width = assembler.width();
          height = assembler.height();
          frame_id = manifest.frame_id;
          completed = MonotonicSeconds();
        }
        complete = whole;
        keyframe_incomplete |= manifest.keyframe && !whole;
      },
      nullptr, 1000);
  const double start = MonotonicSeconds(), deadline = start + globals.timeout;
  bool answered = false;
  while (!complete && MonotonicSeconds() < deadline) {
    // A keyframe that arrived with tiles missing calls for another request (a new id).
    keyframe_incomplete = false;
    const CommandOutcome outcome = client.Send(link.channels.refresh, refresh_request_t{});
    if (outcome.result == CommandOutcome::kRejected) return Report(link, outcome);
    answered |= outcome.result == CommandOutcome::kAccepted;
    counting = true;
    const double wait =
        std::min(deadline - MonotonicSeconds(), answered ? globals.timeout : kRefreshAnswerWait);
    HandleUntil(link.bus, wait, [&] { return complete || keyframe_incomplete; });
  }
  if (!complete) return link.NoAnswer("complete frame");
  const std::string problem = WritePng(path, width, height, picture.data());
  if (!problem.empty()) {
    std::fprintf(stderr, "flagctl: %s\n", problem.c_str());
    return 1;
  }
  std::printf("%s: %d x %d, frame %lld, complete %.0f ms after the request%s\n", path.c_str(), width, height,
              static_cast<long long>(frame_id), 1000 * (completed - start),
              answered
                  ? ""
                  : " (no server answered it: a stream that takes no commands, such as a log playing back)");
  return kOk;
}

int Camera(const Globals& globals, camera_command_t command) {
  Link link(globals);
  CommandClient client(link.bus, link.channels, globals.timeout, globals.signer);
  return Report(link, client.Send(link.channels.camera, command));
}

int SendKeyframe(const Globals& globals, const keyframe_command_t& command) {
  Link link(globals);
  CommandClient client(link.bus, link.channels, globals.timeout, globals.signer);
  return Report(link, client.Send(link.channels.keyframe, command));
}

int Timeline(const Globals& globals) {
  Link link(globals);
  const auto timeline = AwaitMessage<timeline_t>(link.bus, link.channels.timeline, globals.timeout);
  if (!timeline) return link.NoAnswer("TIMELINE");
  PrintTimeline(*timeline, std::cout);
  return kOk;
}

/// Records every channel with the prefix to an LCM log until `duration` or an interrupt.
int Record(const Globals& globals, const std::string& path, double duration) {
  Link link(globals);
  std::unique_ptr<LogRecorder> recorder;
  try {
    recorder = std::make_unique<LogRecorder>(link.bus, link.channels.AllChannels(), path);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "flagctl: %s\n", error.what());
    return kUsage;
  }
  const double start = MonotonicSeconds();
  // A keyframe request first: the server answers with a CHECKPOINT and a full frame, so the log
  // replays (flagd replay) and exports (flagctl export) from its beginning. Recorded meanwhile;
  // nobody may answer (a log playing back), and the recording goes on regardless.
  CommandClient(link.bus, link.channels, std::min(globals.timeout, 1.0), globals.signer)
      .Send(link.channels.refresh, refresh_request_t{});
  while (!g_stop.load() && !recorder->failed()) {
    const double now = MonotonicSeconds();
    if (duration > 0 && now - start >= duration) break;
    if (recorder->events() == 0 && now - start >= globals.timeout && duration == 0) break;
    link.bus.Handle(50);
  }
  if (recorder->failed()) {
    std::fprintf(stderr, "flagctl: writing %s failed after %lld events\n", path.c_str(),
                 static_cast<long long>(recorder->events()));
    return 1;
  }
  std::printf("%s: %lld events, %.1f KB in %.1f s\n", path.c_str(),
              static_cast<long long>(recorder->events()), recorder->bytes() / 1024.0,
              MonotonicSeconds() - start);
  return recorder->events() > 0 ? kOk : link.NoAnswer("message");
}

}  // namespace flagsim
