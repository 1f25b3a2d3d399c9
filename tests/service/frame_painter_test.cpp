// What a frame shows follows the session: the design parameter changes the pattern in the next
// frame, and a reset brings back the scene's.
#include "server/service/frame_painter.hpp"

#include <gtest/gtest.h>

namespace flagsim {
namespace {

TEST(FramePainter, TheDesignParameterChangesTheFlagInTheNextFrame) {
  Scene scene;
  scene.sim.cols = 12;
  scene.sim.rows = 9;
  scene.camera.width = 160;
  scene.camera.height = 96;
  Session session(scene);
  FramePainter painter;
  const std::vector<uint8_t> cross = painter.Paint(FrameInput::Of(session, 0), 1).rgb;
  ParamChange change;
  change.assignments = {{"design", "checker"}};
  ASSERT_EQ(session.ApplyParams(change), "");
  const FrameInput input = FrameInput::Of(session, 0);
  EXPECT_EQ(input.design, render::FlagDesign::kChecker);
  EXPECT_NE(painter.Paint(input, 1).rgb, cross);
  ParamChange reset;
  reset.reset_to_scene = true;
  ASSERT_EQ(session.ApplyParams(reset), "");
  EXPECT_EQ(painter.Paint(FrameInput::Of(session, 0), 1).rgb, cross) << "the scene's design, the flag at rest";
}

}  // namespace
}  // namespace flagsim
