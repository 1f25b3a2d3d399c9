#include "server/service/offline_render.hpp"

#include <algorithm>
#include <utility>

#include "server/parallel/worker_pool.hpp"
#include "server/service/message_builders.hpp"

namespace flagsim {

OfflineRender::OfflineRender(const Scene& scene, double duration, const Channels& channels, LogPublisher* log,
                             FrameSink on_frame)
    : session_(scene),
      duration_(duration),
      tolerance_(scene.sim.dt / 2),
      channels_(channels),
      log_(log),
      on_frame_(std::move(on_frame)),
      journal_(log, channels) {}

bool OfflineRender::done() const { return session_.simulation().state().time + tolerance_ >= duration_; }

double OfflineRender::progress() const {
  return duration_ > 0 ? std::clamp(session_.simulation().state().time / duration_, 0.0, 1.0) : 1.0;
}

bool OfflineRender::Advance() {
  while (!done()) {
    const bool drawn = PublishDue();
    session_.Step();
    ++stats_.steps;
    if (drawn) return true;
  }
  return false;
}

// t => the log's clock => CHECKPOINT, STATE, PARAMS, frame, as each falls due at t
bool OfflineRender::PublishDue() {
  const double time = session_.simulation().state().time;
  if (log_ != nullptr) log_->AdvanceTo(time);
  journal_.AtBoundary(session_, log_ != nullptr ? log_->utime() : 0);  // checkpoints, for replay
  const BoundaryDue due = schedule_.At(session_);
  if (due.state) PublishState();
  if (params_cadence_.Due(time, 1.0, tolerance_)) PublishParams();
  if (due.frame) DrawFrame();
  return due.frame;
}

void OfflineRender::PublishState() {
  if (log_ == nullptr) return;
  log_->Publish(channels_.state, MakeStateMessage(session_, log_->utime()));
  ++stats_.states;
}

void OfflineRender::PublishParams() {
  if (log_ == nullptr) return;
  log_->Publish(channels_.params, MakeParamsMessage(session_.scene(), log_->utime()));
  ++stats_.params;
}

// state => frame => the caller; => changed tiles => the log, paced (tiles, then the manifest)
void OfflineRender::DrawFrame() {
  const int threads = WorkerPool::Shared().Threads(session_.scene().sim.threads);
  const FrameInput input = FrameInput::Of(session_, log_ != nullptr ? log_->utime() : 0);
  const render::Framebuffer& image = painter_.Paint(input, threads);
  const int64_t frame_id = stats_.frames++;
  if (on_frame_) on_frame_(frame_id, image);
  if (log_ == nullptr) return;
  const EncodedFrame frame = tiles_.Encode(image, input.info, threads);
  for (const tile_t& tile : frame.tiles) log_->Enqueue(channels_.tile, Publisher::Encode(tile));
  log_->Enqueue(channels_.frame, Publisher::Encode(frame.manifest));
  stats_.keyframes += frame.manifest.keyframe;
  stats_.tiles += static_cast<int64_t>(frame.tiles.size());
  stats_.tile_bytes += double(frame.encoded_bytes);
}

}  // namespace flagsim
