// A person's image sent to a server in pieces (DESIGN, flagctl's SendDesignFile) on an
// in-process bus: shown whole, the width at its aspect, a bad file refused with nothing changed,
// pieces signed like every command, and a recording of the change replayed bit for bit.
#include <gtest/gtest.h>

#include <random>

#include "client/design_upload.hpp"
#include "client/log_recorder.hpp"
#include "client/stream_reader.hpp"
#include "flagsim/applied_command_t.hpp"
#include "flagsim/design_piece_t.hpp"
#include "server/service/replay.hpp"
#include "tests/common/test_images.hpp"
#include "tests/service/command_intake_fixture.hpp"
#include "tests/service/log_fixtures.hpp"

namespace flagsim {
namespace {

/// A 260 x 130 PNG of noise, its right quarter transparent: three pieces.
std::vector<uint8_t> Pennant() {
  std::mt19937 random(5);
  std::vector<uint8_t> rgba(size_t(260) * 130 * 4);
  for (size_t i = 0; i < rgba.size(); ++i)
    rgba[i] = (i % 4 == 3) ? ((i / 4) % 260 < 195 ? 255 : 0) : uint8_t(random());
  return testing::PngBytes(260, 130, rgba);
}

class DesignCommandTest : public CommandIntakeTest {
 protected:
  DesignCommandTest() {
    SubscribeDecoded<design_piece_t>(bus_, channels_.design_file,
                                     [this](const design_piece_t&) { ++file_pieces_; });
    SubscribeDecoded<applied_command_t>(bus_, channels_.applied, [this](const applied_command_t& applied) {
      if (applied.channel == "DESIGN") ++design_applied_;
    });
  }
  CommandOutcome Send(const std::vector<uint8_t>& bytes, const std::string& name = "pennant.png") {
    return SendDesignFile(client_, channels_.design, name, bytes);
  }
  int file_pieces_ = 0;
  int design_applied_ = 0;
};

TEST_F(DesignCommandTest, AnImageSentInPiecesIsShownWithTheWidthAtItsAspect) {
  const std::vector<uint8_t> bytes = Pennant();
  ASSERT_GT(bytes.size(), size_t(2 * design_piece_t::PIECE_BYTES));
  const CommandOutcome outcome = Send(bytes);
  ASSERT_EQ(outcome.result, CommandOutcome::kAccepted) << outcome.reason;
  EXPECT_EQ(outcome.reason, "design pennant.png (260 x 130 px), the flag 2 m wide");
  EXPECT_EQ(scene().service.design, render::FlagDesign::kImage);
  ASSERT_TRUE(scene().service.design_file);
  EXPECT_EQ(scene().service.design_file->bytes, bytes);
  EXPECT_FALSE(scene().service.design_file->texture.alpha.empty());
  EXPECT_DOUBLE_EQ(scene().sim.width, 2.0);
  EXPECT_EQ(server_.session().simulation().params().width, 2.0);
  EXPECT_EQ(file_pieces_, 3);     // the file, whole, for recordings
  EXPECT_EQ(design_applied_, 1);  // and the piece that completed it, journaled once

  // Back to a built-in design: the image is dropped and the width goes back to 3 : 2.
  ASSERT_EQ(SetParams({"design"}, {"checker"}).result, CommandOutcome::kAccepted);
  EXPECT_FALSE(scene().service.design_file);
  EXPECT_DOUBLE_EQ(scene().sim.width, 1.5);
}

TEST_F(DesignCommandTest, AWidthSetByHandStaysWhenAnImageComes) {
  ASSERT_EQ(SetParams({"width"}, {"1.2"}).result, CommandOutcome::kAccepted);
  ASSERT_EQ(Send(Pennant()).result, CommandOutcome::kAccepted);
  EXPECT_DOUBLE_EQ(scene().sim.width, 1.2);
  EXPECT_EQ(scene().service.design, render::FlagDesign::kImage);
}

TEST_F(DesignCommandTest, ABadFileIsRefusedAndChangesNothing) {
  std::vector<uint8_t> truncated = Pennant();
  truncated.resize(truncated.size() - 4000);  // whole pieces, a whole digest: a bad PNG
  const auto values = Values();
  const CommandOutcome outcome = Send(truncated, "cut.png");
  EXPECT_EQ(outcome.result, CommandOutcome::kRejected);
  EXPECT_EQ(outcome.reason.rfind("cut.png: the PNG cannot be decoded", 0), 0u) << outcome.reason;
  EXPECT_EQ(Values(), values);
  EXPECT_FALSE(scene().service.design_file);
  EXPECT_EQ(file_pieces_, 0);
  EXPECT_EQ(design_applied_, 0);
  // design=image without an image is refused too.
  const CommandOutcome by_name = SetParams({"design"}, {"image"});
  EXPECT_EQ(by_name.result, CommandOutcome::kRejected);
  EXPECT_EQ(by_name.reason.rfind("design: image shows a person's own image, which comes as a file", 0), 0u);
}

TEST_F(DesignCommandTest, ARecordingOfTheChangeReplaysBitForBit) {
  const std::string path = testing::TempPath("design.lcmlog");
  {
    LogRecorder recorder(bus_, channels_, path);
    ASSERT_EQ(client_.Send(channels_.refresh, refresh_request_t{}).result, CommandOutcome::kAccepted);
    clock_.StepUntil(server_, [&] { return recorder.checkpoints() > 0; });
    for (int i = 0; i < 40; ++i) clock_.Step(server_);
    ASSERT_EQ(Send(Pennant()).result, CommandOutcome::kAccepted);
    for (int i = 0; i < 300; ++i) clock_.Step(server_);
    ASSERT_EQ(SetParams({"design"}, {"tricolour"}).result, CommandOutcome::kAccepted);
    for (int i = 0; i < 300; ++i) clock_.Step(server_);
  }
  const ReplayReport report = Replay(path, {});
  EXPECT_TRUE(report.ok()) << report.error << report.divergence;
  EXPECT_EQ(report.commands, 2);
  EXPECT_GT(report.states_checked, 60);  // STATE at 60 Hz of 640 steps of 2 ms
}

TEST_F(DesignCommandTest, ARecordingThatBeginsAfterTheChangeHasTheImage) {
  ASSERT_EQ(Send(Pennant()).result, CommandOutcome::kAccepted);
  for (int i = 0; i < 40; ++i) clock_.Step(server_);
  const std::string path = testing::TempPath("design_later.lcmlog");
  {
    LogRecorder recorder(bus_, channels_, path);
    ASSERT_EQ(client_.Send(channels_.refresh, refresh_request_t{}).result, CommandOutcome::kAccepted);
    clock_.StepUntil(server_, [&] { return recorder.checkpoints() > 0; });
    for (int i = 0; i < 200; ++i) clock_.Step(server_);
  }
  const ReplayReport report = Replay(path, {});
  EXPECT_TRUE(report.ok()) << report.error << report.divergence;
  EXPECT_EQ(report.first_reason, "refresh");
  EXPECT_GT(report.states_checked, 15);  // 200 steps of 2 ms at 60 Hz
}

}  // namespace
}  // namespace flagsim
