#include "server/service/frame_stage.hpp"

#include <utility>

#include "messages/utime.hpp"
#include "server/parallel/worker_pool.hpp"

namespace flagsim {

FrameStage::FrameStage(Sink sink) : sink_(std::move(sink)), thread_([this] { Run(); }) {}

FrameStage::~FrameStage() { Stop(); }

void FrameStage::Stop() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  if (!thread_.joinable()) return;
  thread_.join();
  painter_ = FramePainter();
  tiles_ = TileStream();
}

bool FrameStage::Busy() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return job_.has_value();
}

void FrameStage::Submit(FrameInput input, int threads, int64_t keyframe_request) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    job_ = Job{std::move(input), threads, keyframe_request};
  }
  wake_.notify_one();
}

void FrameStage::Drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return !job_.has_value(); });
}

FrameStageStats FrameStage::TakeStats() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return std::exchange(stats_, FrameStageStats{});
}

// wait for a job => process it (the job stays in place, so Busy() holds) => clear it
void FrameStage::Run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stopping_ || job_.has_value(); });
    if (!job_.has_value()) return;  // stopping, nothing in hand
    lock.unlock();
    Process(*job_);  // only this thread touches the job until it is cleared
    lock.lock();
    job_.reset();
    idle_.notify_all();
  }
}

// copied state => frame => changed tiles => sink
void FrameStage::Process(const Job& job) {
  const double start = MonotonicSeconds();
  const int threads = WorkerPool::Shared().Threads(job.threads);
  const render::Framebuffer& image = painter_.Paint(job.input, threads);
  const double painted = MonotonicSeconds();
  if (job.keyframe_request >= 0) tiles_.RequestKeyframe(job.keyframe_request);
  const EncodedFrame frame = tiles_.Encode(image, job.input.info, threads);
  const double encoded = MonotonicSeconds();
  sink_(frame);
  const std::lock_guard<std::mutex> lock(mutex_);
  ++stats_.frames;
  stats_.render_seconds += painted - start;
  stats_.encode_seconds += encoded - painted;
  stats_.tiles += static_cast<int64_t>(frame.tiles.size());
  stats_.tile_bytes += double(frame.encoded_bytes);
}

}  // namespace flagsim
