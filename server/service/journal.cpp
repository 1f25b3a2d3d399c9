#include "server/service/journal.hpp"

#include "flagsim/applied_command_t.hpp"
#include "flagsim/refresh_request_t.hpp"
#include "server/service/checkpoint_codec.hpp"

namespace flagsim {

void Journal::AtBoundary(Session* session, int64_t utime) {
  const int64_t step = session->simulation().state().step;
  if (PeriodicCheckpointAt(step)) PublishCheckpoint(session, step == 0 ? "start" : "periodic", utime);
}

void Journal::Refresh(Session* session, int64_t request, int64_t utime) {
  if (publisher_ == nullptr) {
    session->CleanSnapshot();
    return;
  }
  refresh_request_t command{};
  command.utime = utime;
  command.client_id = "flagd";
  command.sequence = request;
  const std::vector<uint8_t> bytes = Publisher::Encode(command);
  Applied(*session, channels_.refresh, bytes.data(), bytes.size(), utime);
  PublishCheckpoint(session, "refresh", utime);
}

void Journal::End(Session* session, int64_t utime) { PublishCheckpoint(session, "end", utime); }

void Journal::Applied(const Session& session, const std::string& channel, const uint8_t* data, size_t size,
                      int64_t utime) {
  if (publisher_ == nullptr) return;
  applied_command_t message{};
  message.utime = utime;
  message.step = session.simulation().state().step;
  message.channel = channels_.Unprefixed(channel);
  message.data.assign(data, data + size);
  message.num_bytes = static_cast<int32_t>(size);
  publisher_->Publish(channels_.applied, message);
}

void Journal::PublishCheckpoint(Session* session, const std::string& reason, int64_t utime) {
  const SessionSnapshot snapshot = session->CleanSnapshot();
  if (publisher_ != nullptr)
    publisher_->Publish(channels_.checkpoint, MakeCheckpointMessage(snapshot, reason, utime));
}

}  // namespace flagsim
