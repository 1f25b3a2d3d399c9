#include "tests/fuzz/command_server.hpp"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <cstdlib>

#include "flagsim/ack_t.hpp"
#include "flagsim/applied_command_t.hpp"
#include "flagsim/checkpoint_t.hpp"
#include "flagsim/design_piece_t.hpp"
#include "messages/checked_decode.hpp"
#include "messages/utime.hpp"
#include "server/service/checkpoint_codec.hpp"
#include "server/service/command_apply.hpp"

namespace flagsim::fuzz {
namespace {

constexpr size_t kMaxPublished = 256 << 20;

template <class Message>
Message Decoded(const uint8_t* data, size_t size) {
  std::string error;
  std::optional<Message> message = wire::CheckedDecode<Message>(data, size, kMaxPublished, &error);
  Require(message.has_value(),
          std::string("the server published a ") + Message::getTypeName() + " its own readers refuse", error);
  return *message;
}

}  // namespace

Scene SmallScene() {
  Scene scene;
  scene.sim.cols = 6;
  scene.sim.rows = 4;
  scene.sim.threads = 1;
  scene.camera.width = 64;
  scene.camera.height = 48;
  return scene;
}

void QuietLogs() {
  if (std::getenv("FLAGSIM_FUZZ_LOG") == nullptr) spdlog::set_level(spdlog::level::off);
}

void Require(bool ok, const std::string& what, const std::string& detail) {
  if (ok) return;
  std::fprintf(stderr, "fuzz check failed: %s%s%s\n", what.c_str(), detail.empty() ? "" : ": ",
               detail.c_str());
  std::abort();
}

CommandServer::CommandServer(Bus& bus, const Channels& channels, std::vector<CommandKey> keys)
    : bus_(bus),
      session_(SmallScene()),
      presence_(bus, channels),
      journal_(&bus, channels),
      intake_(bus, channels, session_, stats_, std::move(keys)),
      replayed_(SmallScene()) {
  intake_.SetJournal(&journal_);
  intake_.SetPresence(&presence_);
  bus.Subscribe(channels.ack,
                [this](const std::string&, const uint8_t* data, size_t size) { CheckAck(data, size); });
  bus.Subscribe(channels.checkpoint, [this](const std::string&, const uint8_t* data, size_t size) {
    CheckCheckpoint(data, size);
  });
  bus.Subscribe(channels.applied,
                [this](const std::string&, const uint8_t* data, size_t size) { Replay(data, size); });
  bus.Subscribe(channels.design_file, [this](const std::string&, const uint8_t* data, size_t size) {
    Require(designs_.Add(Decoded<design_piece_t>(data, size)).empty(), "a DESIGN_FILE piece is refused");
  });
  journal_.AtBoundary(session_, UnixMicros());  // the first checkpoint, as the server's first tick
}

void CommandServer::HandleAll() {
  bus_.HandleAll();
  if (intake_.TakeRefreshRequest() >= 0) {
    journal_.Refresh(session_, UnixMicros());
    bus_.HandleAll();
  }
}

void CommandServer::Step() {
  session_.Step();
  replayed_.Step();
  intake_.AfterStep();
  journal_.AtBoundary(session_, UnixMicros());
  HandleAll();
}

void CommandServer::Finish() {
  intake_.FlushPending();
  HandleAll();
  Require(replayed_.simulation().Hash() == session_.simulation().Hash(),
          "the session replayed from APPLIED ends with another state hash than the live one");
}

void CommandServer::CheckAck(const uint8_t* data, size_t size) { Decoded<ack_t>(data, size); }

void CommandServer::CheckCheckpoint(const uint8_t* data, size_t size) {
  const checkpoint_t checkpoint = Decoded<checkpoint_t>(data, size);
  SessionSnapshot snapshot;
  const std::string problem = ReadCheckpoint(checkpoint, &snapshot, &designs_);
  Require(problem.empty(), "a CHECKPOINT the server published does not read back", problem);
}

// APPLIED => the same command, at the same step, into the replayed session
void CommandServer::Replay(const uint8_t* data, size_t size) {
  const applied_command_t applied = Decoded<applied_command_t>(data, size);
  Require(applied.step == replayed_.simulation().state().step,
          "APPLIED names another step than the session's", std::to_string(applied.step));
  const std::string problem = ApplyCommandBytes(applied.channel, applied.data, &replayed_, &designs_);
  Require(problem.empty(), "a command the server applied is refused in the replay", problem);
}

}  // namespace flagsim::fuzz
