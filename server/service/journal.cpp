#include "server/service/journal.hpp"

#include "flagsim/applied_command_t.hpp"
#include "messages/design_pieces.hpp"
#include "server/service/checkpoint_codec.hpp"

namespace flagsim {

void Journal::AtBoundary(const Session& session, int64_t utime) {
  const int64_t step = session.simulation().state().step;
  if (PeriodicCheckpointAt(step) && step != resumed_step_)
    PublishCheckpoint(session, step == 0 ? "start" : "periodic", utime);
}

void Journal::Resumed(const Session& session, int64_t utime) {
  resumed_step_ = session.simulation().state().step;
  PublishCheckpoint(session, "resume", utime);
}

void Journal::Refresh(const Session& session, int64_t utime) { PublishCheckpoint(session, "refresh", utime); }

void Journal::End(const Session& session, int64_t utime) { PublishCheckpoint(session, "end", utime); }

void Journal::Applied(const Session& session, const std::string& channel, const uint8_t* data, size_t size,
                      const Sender& sender, int64_t utime) {
  if (publisher_ == nullptr) return;
  applied_command_t message{};
  message.utime = utime;
  message.step = session.simulation().state().step;
  message.channel = channels_.Unprefixed(channel);
  message.client_id = sender.client_id;
  message.key_id = sender.key_id;
  message.data.assign(data, data + size);
  message.num_bytes = static_cast<int32_t>(size);
  publisher_->Publish(channels_.applied, message);
}

void Journal::DesignFile(const flagsim::DesignFile& file, const std::string& client_id, int64_t utime) {
  if (publisher_ == nullptr) return;
  for (const design_piece_t& piece : SplitDesignFile(file.name, file.digest, file.bytes, client_id, utime))
    publisher_->Publish(channels_.design_file, piece);
}

// The design files the checkpoint names go first (a periodic or end checkpoint names the ones
// sent before it).
void Journal::PublishCheckpoint(const Session& session, const std::string& reason, int64_t utime) {
  if (publisher_ == nullptr) return;
  if (reason != "periodic" && reason != "end") {
    const DesignFilePtr& now = session.scene().service.design_file;
    const DesignFilePtr& initial = session.initial_scene().service.design_file;
    if (now) DesignFile(*now, "flagd", utime);
    if (initial && (!now || initial->digest != now->digest)) DesignFile(*initial, "flagd", utime);
  }
  publisher_->Publish(channels_.checkpoint, MakeCheckpointMessage(session.Snapshot(), reason, utime));
}

}  // namespace flagsim
