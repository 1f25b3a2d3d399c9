// Outgoing messages built from the session: STATE, PARAMS, STATUS, TIMELINE, and what a frame's
// manifest says of the session. Pure functions of what they read, so tests can check them
// without a bus.
#pragma once

#include <cstdint>

#include "flagsim/params_t.hpp"
#include "flagsim/state_t.hpp"
#include "flagsim/status_t.hpp"
#include "flagsim/timeline_t.hpp"
#include "server_stats.hpp"
#include "session.hpp"
#include "tile_stream.hpp"

namespace flagsim {

/// The flag's nodes now: positions, grid, pole, mean wind, hash.
state_t MakeStateMessage(const Session& session, int64_t utime);

/// STATE messages per second of simulated time: the scene's rate, or 1 Hz while the flag
/// sleeps (it does not move; once a second says so).
double StateRate(const Session& session);

/// The step, time and camera of a frame drawn now, for its manifest.
FrameInfo MakeFrameInfo(const Session& session, int64_t utime);

/// The parameter table with the session's current values.
params_t MakeParamsMessage(const Scene& scene, int64_t utime);

/// The timeline: its keys (what each sets), play state and position; `step` the step it stands at.
timeline_t MakeTimelineMessage(const sim::Timeline& timeline, int64_t step, int64_t utime);

/// What passed since the last STATUS.
struct StatusWindow {
  double wall_seconds = 0;  ///< s of wall time
  double sim_seconds = 0;   ///< s of simulated time
  double bytes = 0;         ///< bytes published
  double uptime = 0;        ///< s since the server started
};

/// Health over the window: rates, mean times, counters.
status_t MakeStatusMessage(const Session& session, const ServerStats& stats, const StatusWindow& window,
                           int64_t utime);

}  // namespace flagsim
