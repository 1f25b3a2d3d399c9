// flagd render: a scene's session stepped as fast as it goes, with no bus and no commands,
// publishing what a live server would into an event log, on simulated time. At each step
// boundary t before the duration:
//
//   CHECKPOINT at 0 and every Journal::kCheckpointSteps steps, so that flagd replay checks it
//   STATE    when the live server's BoundarySchedule says, at the same steps
//   PARAMS   at 0 and every simulated second
//   frame    when BoundarySchedule says: draw; the image to the caller (PNG frames); the changed
//            tiles picked and compressed by the live server's TileStream (a keyframe first, then
//            the rolling refresh), logged paced as the live server sends them, then the FRAME
//            manifest
//   step     one dt
//
// Without a log only the frames are drawn and handed over.
#pragma once

#include <cstdint>
#include <functional>

#include "messages/channels.hpp"
#include "server/scene/scene.hpp"
#include "server/service/boundary_schedule.hpp"
#include "server/service/frame_painter.hpp"
#include "server/service/journal.hpp"
#include "server/service/log_publisher.hpp"
#include "server/service/session.hpp"
#include "server/service/sim_cadence.hpp"
#include "server/service/tile_stream.hpp"

namespace flagsim {

/// What a render has written so far.
struct OfflineRenderStats {
  int64_t steps = 0;
  int64_t states = 0;     ///< STATE messages
  int64_t params = 0;     ///< PARAMS messages
  int64_t frames = 0;     ///< frames drawn
  int64_t keyframes = 0;  ///< of them, with every tile
  int64_t tiles = 0;      ///< TILE messages
  double tile_bytes = 0;  ///< compressed tile payloads
};

class OfflineRender {
 public:
  /// Called with each frame drawn: its id (0, 1, ...: the FRAME manifest's) and its image.
  using FrameSink = std::function<void(int64_t frame_id, const render::Framebuffer& image)>;

  /// Renders `duration` s of simulated time of `scene`; `log` may be null (frames only).
  OfflineRender(const Scene& scene, double duration, const Channels& channels, LogPublisher* log,
                FrameSink on_frame);

  /// Steps on to the next frame drawn, publishing what falls due on the way. Returns false
  /// once the duration is done (nothing more to draw or publish).
  bool Advance();

  bool done() const;
  double progress() const;  ///< fraction of the duration simulated, 0 .. 1
  const OfflineRenderStats& stats() const { return stats_; }
  const Session& session() const { return session_; }

 private:
  /// Publishes and draws what falls due at the current step boundary; true if a frame was drawn.
  bool PublishDue();
  void PublishState();
  void PublishParams();
  void DrawFrame();

  Session session_;
  double duration_;   ///< s, simulated
  double tolerance_;  ///< s: half a step, so that a time a rounding error short still counts
  const Channels& channels_;
  LogPublisher* log_;
  FrameSink on_frame_;
  Journal journal_;
  FramePainter painter_;
  TileStream tiles_;
  BoundarySchedule schedule_;  ///< STATE and frames, as the live server publishes them
  SimCadence params_cadence_;
  OfflineRenderStats stats_;
};

}  // namespace flagsim
