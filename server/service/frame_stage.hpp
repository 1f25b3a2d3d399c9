// The frame half of the server's pipeline, on a thread of its own:
//
//   loop's thread    at a frame time: FrameInput::Of(session) => Submit, and back to stepping
//   stage's thread   paint => hash the tiles, pick and compress the changed ones => the sink
//                    (the paced publisher), while the loop steps toward the next frame
//
// Both halves hand their loops to the one worker pool (parallel/worker_pool.hpp), so the cores
// go to whichever has work. One frame is in the stage at a time: the caller asks Busy() and skips
// a frame due while the last is still being drawn, never queues it. The stage's output depends
// only on the inputs submitted, in order, so it is the same at any thread count.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

#include "server/service/frame_painter.hpp"
#include "server/service/tile_stream.hpp"

namespace flagsim {

/// What the stage did since it was last asked.
struct FrameStageStats {
  int64_t frames = 0;
  double render_seconds = 0;  ///< wall time spent drawing
  double encode_seconds = 0;  ///< wall time spent hashing and compressing tiles
  int64_t tiles = 0;
  double tile_bytes = 0;  ///< compressed tile payloads
};

class FrameStage {
 public:
  /// Receives each frame's messages on the stage's thread, in order.
  using Sink = std::function<void(const EncodedFrame&)>;

  explicit FrameStage(Sink sink);
  ~FrameStage();  ///< Stop()
  FrameStage(const FrameStage&) = delete;
  FrameStage& operator=(const FrameStage&) = delete;

  /// Whether a frame is still being drawn or encoded.
  bool Busy() const;

  /// Hands a frame to the stage (call when not Busy). keyframe_request >= 0: the frame is a
  /// keyframe answering that REFRESH. Drawn and encoded on `threads` threads.
  void Submit(FrameInput input, int threads, int64_t keyframe_request);

  /// Waits until the frame in hand, if any, has gone to the sink.
  void Drain();

  /// Finishes the frame in hand, stops the stage's thread and lets go of what drawing and
  /// encoding hold (the renderer's buffers, the tiles' hashes): for a server at its end, so that
  /// its last checkpoint is not built beside them. No Submit after it.
  void Stop();

  /// The counts and timings since the last call.
  FrameStageStats TakeStats();

 private:
  struct Job {
    FrameInput input;
    int threads = 1;
    int64_t keyframe_request = -1;
  };
  void Run();
  void Process(const Job& job);

  Sink sink_;
  FramePainter painter_;  ///< the stage thread's own
  TileStream tiles_;      ///< the stage thread's own
  mutable std::mutex mutex_;
  std::condition_variable wake_;  ///< the stage: a job, or stopping
  std::condition_variable idle_;  ///< Drain: the job is done
  std::optional<Job> job_;        ///< submitted or in hand
  FrameStageStats stats_;
  bool stopping_ = false;
  std::thread thread_;  ///< last: starts when everything above is ready
};

}  // namespace flagsim
