// Fuzz target: the LCM event log reader (messages/event_log_reader.hpp) as flagctl export uses
// it. The input is the log file: every event is read (all data, and with a channel filter that
// skips the data of the others), then export's two passes: the survey (frame and parameter
// events: size, frame rate) and the frames (tiles assembled, hash-checked, the timing kept),
// taking every image it gives as the video writer would.
#include <cstddef>
#include <cstdint>
#include <string>

#include "client/log_frames.hpp"
#include "messages/channels.hpp"
#include "messages/event_log_reader.hpp"
#include "tests/fuzz/scratch_file.hpp"

using namespace flagsim;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static fuzz::ScratchFile file("event_log");
  const std::string& path = file.Hold(data, size);
  const Channels channels;

  EventLogReader whole(path);
  LogEvent event;
  while (whole.Next(&event)) {
  }
  EventLogReader filtered(path);
  while (
      filtered.Next(&event, [&channels](const std::string& channel) { return channel == channels.tile; })) {
  }

  const LogSurvey survey = SurveyLog(path, channels);
  LogFrames frames(path, channels, survey.frame_rate);
  while (frames.Next()) {
  }
  return 0;
}
