// flagctl export: a log's frames into PNGs or a video, or the whole session into MCAP.
//
//   NAME.mcap  the live view's channels, offline (gateway/mcap_export.hpp); otherwise:
//   survey    FRAME and PARAMS only: is there a keyframe, what size, what frame rate
//   frames    TILE and FRAME through the assembler (log_frames.hpp): whole images, the
//             timing kept (lost and missing frames repeat the last whole one)
//   output    PNG files, or ffmpeg fed down a pipe (frame_output.hpp)
//   report    what was skipped, repeated or dropped, and where a damaged log stopped
#include <atomic>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/cli_checks.hpp"
#include "client/flagctl_commands.hpp"
#include "client/frame_output.hpp"
#include "client/gateway/mcap_export.hpp"
#include "client/log_frames.hpp"
#include "common/progress_bar.hpp"
#include "messages/event_log_reader.hpp"

namespace flagsim {
namespace {

struct ExportRequest {
  std::string log_path;   ///< an LCM event log
  std::string output;     ///< DIR/ (PNG frames), NAME.mp4 or NAME.gif
  double frame_rate = 0;  ///< Hz of the video; 0: the log's own
};

constexpr double kFallbackFrameRate = 30;  ///< Hz, for a log that tells none (a single frame)

void Note(int64_t count, const char* what) {
  if (count > 0) std::fprintf(stderr, "flagctl export: note: %lld %s\n", static_cast<long long>(count), what);
}

/// What the log held that did not go into the output as it was.
void ReportSkips(const LogFramesReport& report) {
  Note(report.skipped_before_whole,
       "frame(s) before the first whole frame skipped (recorded mid-stream: the rolling refresh "
       "completes the picture within a second)");
  Note(report.lost,
       "frame(s) with tiles missing (the frame hash did not check out): each repeats the last whole frame");
  Note(report.gaps, "frame time(s) with no frame (the server skipped them): each repeats the last frame");
  Note(report.dropped, "frame(s) between two frame times dropped (extra keyframes asked for by REFRESH)");
  Note(report.time_jumps, "jump(s) in simulated time (a new session in the log): counted afresh from there");
  Note(report.undecodable, "TILE or FRAME event(s) that were not one ignored");
  Note(report.refused_tiles, "tile(s) refused by the assembler (bad data)");
}

/// Exit code and message for a log that holds nothing to export.
int NothingToExport(const ExportRequest& request, const Channels& channels, const LogSurvey& survey) {
  if (!survey.problem.empty()) std::fprintf(stderr, "flagctl export: %s\n", survey.problem.c_str());
  std::fprintf(
      stderr, "flagctl export: %s holds no complete frame on %s (%lld FRAME events, %lld keyframes)%s\n",
      request.log_path.c_str(), channels.frame.c_str(), static_cast<long long>(survey.manifests),
      static_cast<long long>(survey.keyframes),
      survey.manifests == 0 && survey.problem.empty() ? "; is the server's channel prefix another (--prefix)?"
                                                      : "");
  return kNothingToExport;
}

/// What was written: frames, size, rate, and for a video the frames fitted to its size.
std::string Summary(const ExportRequest& request, const FrameOutput& output, OutputKind kind,
                    const LogSurvey& survey, const LogFrames& frames, bool sizes_vary, double frame_rate,
                    const std::string& rate_source) {
  const bool video = kind != OutputKind::kPngDirectory;
  char line[640];
  std::snprintf(line, sizeof(line), "%s: %lld frames, %s%d x %d px, %.6g frames per second (%s)",
                request.output.c_str(), static_cast<long long>(output.frames()),
                sizes_vary && !video ? "the last " : "", video ? survey.width : frames.width(),
                video ? survey.height : frames.height(), frame_rate, rate_source.c_str());
  std::string summary = line;
  if (output.fitted() > 0) {
    std::snprintf(line, sizeof(line),
                  "\nflagctl export: note: %lld frame(s) of another size than the first (%d x %d) scaled "
                  "to fit it, keeping their shape, on black",
                  static_cast<long long>(output.fitted()), survey.width, survey.height);
    summary += line;
  }
  return summary;
}

/// The log's survey and frames; throws std::runtime_error if it cannot be read.
std::unique_ptr<LogFrames> OpenLog(const ExportRequest& request, const Channels& channels,
                                   LogSurvey* survey) {
  *survey = SurveyLog(request.log_path, channels);
  return std::make_unique<LogFrames>(request.log_path, channels, survey->frame_rate);
}

/// The frame rate of the output, and where it comes from, for the summary.
std::pair<double, std::string> FrameRate(const ExportRequest& request, const LogSurvey& survey) {
  if (request.frame_rate > 0) return {request.frame_rate, "--fps"};
  if (survey.frame_rate > 0) return {survey.frame_rate, "the log's " + survey.frame_rate_source};
  return {kFallbackFrameRate, "the log tells none"};
}

/// Frames into the output until the log ends, the output fails or `stop`, then the output
/// finished; "" or what went wrong. Notes whether the frames' sizes vary.
std::string WriteFrames(LogFrames& frames, const LogSurvey& survey, const std::atomic<bool>& stop,
                        FrameOutput* output, ProgressBar* bar, bool* sizes_vary) {
  std::string problem;
  while (problem.empty() && !stop.load() && frames.Next()) {
    *sizes_vary |= frames.width() != survey.width || frames.height() != survey.height;
    problem = output->Write(frames.image().data(), frames.width(), frames.height());
    const EventLogReader& reader = frames.reader();
    bar->Update(reader.size() > 0 ? double(reader.offset()) / double(reader.size()) : 1.0,
                "frame " + std::to_string(frames.images()));
  }
  const std::string finished = output->Finish();
  return problem.empty() ? finished : problem;
}

/// What is checked before any work: the log can be read (else 1), the output's name says what to
/// write (else 2), its directory is there to write in (else 1). kOk with *kind, or the exit code.
int CheckRequest(const ExportRequest& request, OutputKind* kind) {
  try {
    EventLogReader probe(request.log_path);
  } catch (const std::runtime_error& error) {
    std::fprintf(stderr, "flagctl export: %s\n", error.what());
    return kFailed;
  }
  std::string problem;
  const std::optional<OutputKind> named = OutputKindOf(request.output, &problem);
  if (!named) {
    std::fprintf(stderr, "flagctl export: -o %s\n", problem.c_str());
    return kUsage;
  }
  *kind = *named;
  problem = CheckOutputPath(*kind, request.output);
  if (problem.empty()) return kOk;
  std::fprintf(stderr, "flagctl export: %s\n", problem.c_str());
  return kFailed;
}

bool IsMcap(const std::string& output) {
  return output.size() > 5 && output.compare(output.size() - 5, 5, ".mcap") == 0;
}

/// The session in a log, as the live view's channels, into MCAP; `stop` ends it early.
int ExportToMcap(const Globals& globals, const ExportRequest& request, const std::atomic<bool>& stop) {
  if (request.frame_rate > 0) {
    std::fprintf(stderr, "flagctl export: --fps is for videos; MCAP keeps every message at its own time\n");
    return kUsage;
  }
  ProgressBar bar;
  gateway::McapExportReport report;
  try {
    report = gateway::ExportMcap(request.log_path, request.output, Channels(globals.prefix), stop,
                                 [&bar](double fraction) { bar.Update(fraction, "reading the log"); });
  } catch (const std::runtime_error& error) {
    bar.Finish(std::string("flagctl export: ") + error.what());
    return kFailed;
  }
  std::string summary = request.output + ": " + std::to_string(report.total()) + " messages";
  for (const auto& [topic, count] : report.messages) summary += ", " + std::to_string(count) + " on " + topic;
  bar.Finish(summary);
  Note(report.incomplete_frames, "frame(s) with tiles missing: no image for them");
  Note(report.undecodable, "event(s) on the server's channels that were not their type ignored");
  if (!report.log_problem.empty())
    std::fprintf(stderr, "flagctl export: %s; exported everything before it\n", report.log_problem.c_str());
  if (stop.load()) {
    std::fprintf(stderr, "flagctl export: interrupted; %s holds the messages so far\n", request.output.c_str());
    return kFailed;
  }
  if (report.total() > 0) return kOk;
  std::fprintf(stderr, "flagctl export: %s holds nothing on %s*; is the server's channel prefix another (--prefix)?\n",
               request.log_path.c_str(), globals.prefix.c_str());
  return kNothingToExport;
}

/// The frames in a log, assembled and hash-checked, into PNGs or a video; `stop` ends it early.
int Export(const Globals& globals, const ExportRequest& request, const std::atomic<bool>& stop) {
  if (IsMcap(request.output)) return ExportToMcap(globals, request, stop);
  OutputKind kind = OutputKind::kPngDirectory;
  const int checked = CheckRequest(request, &kind);
  if (checked != kOk) return checked;
  const Channels channels(globals.prefix);
  LogSurvey survey;
  std::unique_ptr<LogFrames> frames;
  try {
    frames = OpenLog(request, channels, &survey);
  } catch (const std::runtime_error& error) {
    std::fprintf(stderr, "flagctl export: %s\n", error.what());
    return kFailed;
  }
  if (survey.manifests == 0) return NothingToExport(request, channels, survey);
  const auto [rate, rate_source] = FrameRate(request, survey);
  const std::unique_ptr<FrameOutput> output = MakeFrameOutput(kind, request.output, rate);

  ProgressBar bar;
  bool sizes_vary = false;
  const std::string problem = WriteFrames(*frames, survey, stop, output.get(), &bar, &sizes_vary);
  if (!problem.empty()) {  // what went wrong, and no summary of what was not written
    bar.Finish("flagctl export: " + problem);
    return kFailed;
  }
  bar.Finish(output->frames() > 0
                 ? Summary(request, *output, kind, survey, *frames, sizes_vary, rate, rate_source)
                 : "flagctl export: no frame written");

  ReportSkips(frames->report());
  if (!frames->reader().problem().empty()) {
    std::fprintf(stderr, "flagctl export: %s; exported everything before it\n",
                 frames->reader().problem().c_str());
  }
  if (stop.load()) {
    std::fprintf(stderr, "flagctl export: interrupted; %s holds the frames so far\n", request.output.c_str());
    return kFailed;
  }
  return frames->images() > 0 ? kOk : NothingToExport(request, channels, survey);
}

}  // namespace

std::string ExportLogTo(const Globals& globals, const std::string& log, const std::string& output,
                        const std::atomic<bool>& stop) {
  const int code = Export(globals, ExportRequest{log, output, 0}, stop);
  if (code == kOk) return "";
  return "flagctl export of " + log + " to " + output + " ended with exit code " + std::to_string(code) +
         " (its reason is on the gateway's output)";
}

void AddExportCommand(CLI::App& app, Invocation& invocation) {
  const auto request = std::make_shared<ExportRequest>();
  ExportRequest& export_request = *request;
  CLI::App* export_command =
      app.add_subcommand("export", "turn the frames in an LCM log into PNGs, an MP4 or a GIF, or the session into MCAP");
  export_command
      ->add_option("log", export_request.log_path, "the log (flagctl record, flagd render, lcm-logger)")
      ->required();
  export_command
      ->add_option(
          "-o,--output", export_request.output,
          "DIR/ or an existing directory: PNG frames frame_%06d.png; NAME.mp4: H.264 video; NAME.gif; "
          "NAME.mcap: the live view's channels (image, 3D scene, plots, tables) for Foxglove or Lichtblick")
      ->required();
  export_command
      ->add_option(
          "--fps", export_request.frame_rate,
          "frames per second of the video (default: the log's frame rate, from its PARAMS or FRAME times)")
      ->check(AboveZero());
  export_command->footer(
      "Reads the TILE and FRAME events with the prefix (--prefix) and assembles them as a client\n"
      "would; every frame written has the server's frame hash. A log recorded mid-stream starts at its\n"
      "first keyframe (earlier frames are skipped, with a note). The log's timing is kept: a frame whose\n"
      "tiles were lost (its hash does not check out), and a frame time the server skipped, repeat the\n"
      "last whole frame, so there is one image per frame time. A log cut short (a recorder killed\n"
      "mid-write) is exported up to its last whole event, with a message naming the byte and event where\n"
      "it stops. Videos are made by ffmpeg (Debian's ffmpeg package) and keep the first frame's size:\n"
      "a later frame of another size (a camera size command mid-session) is scaled to fit it, keeping\n"
      "its shape, centred on black. PNG frames keep each its own size.\n"
      "NAME.mcap holds the channels and schemas the live view's gateway serves (/flag/image as JPEG,\n"
      "/flag/scene, /flag/state, /flag/status, /flag/params, /flag/timeline, /flag/camera, /flag/acks),\n"
      "each message at its log time: open it in Foxglove or Lichtblick.\n"
      "Exit codes: 0 ok (also for a log cut short), 1 the log cannot be read, the output cannot be\n"
      "written, or ffmpeg is missing or failed, 2 usage, 5 no complete frame in the log.");

  invocation.RunOnParse(export_command, [&invocation, request] {
    return Export(invocation.globals, *request, invocation.stop);
  });
}

}  // namespace flagsim
