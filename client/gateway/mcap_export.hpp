// A recorded session for the tools people open offline: an LCM log turned into MCAP with the
// channels and schemas the gateway serves live (gateway_catalog.hpp), so that Foxglove and
// Lichtblick show the same picture, 3D scene and plots from the file as from the live view.
//
//   TILE, FRAME  ==> FrameMirror (hash-checked whole frames) ==> /flag/image (JPEG), /flag/camera
//   STATE        ==> /flag/state (the plots' summary), /flag/scene (the cloth in 3D)
//   STATUS, PARAMS, TIMELINE, ACK ==> /flag/status, /flag/params, /flag/timeline, /flag/acks
//
// Each message keeps the log's time (log_time) and the server's stamp (publish_time). A new
// server in the log (another server id) starts its frames afresh, as the gateway does live.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "messages/channels.hpp"

namespace flagsim::gateway {

struct McapExportReport {
  std::map<std::string, int64_t> messages;  ///< written, by topic
  int64_t undecodable = 0;                  ///< events on the server's channels that were not their type
  int64_t incomplete_frames = 0;            ///< FRAMEs whose tiles did not all arrive: no image
  std::string log_problem;                  ///< how the log ended if not cleanly
  int64_t total() const;
};

/// Writes the session on `channels` in the log at `log_path` to `mcap_path`. `progress(f)` is told
/// the fraction of the log read; `stop` ends it early (the file is then closed as it stands).
/// Throws std::runtime_error naming the file when the log cannot be read or the MCAP written.
McapExportReport ExportMcap(const std::string& log_path, const std::string& mcap_path, const Channels& channels,
                            const std::atomic<bool>& stop, const std::function<void(double)>& progress = nullptr);

}  // namespace flagsim::gateway
