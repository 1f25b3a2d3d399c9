// flagctl camera: the camera's moves, one subcommand each, into one CAMERA command. Angles are
// typed in degrees and sent in rad; distances in m.
#include <cmath>
#include <memory>
#include <vector>

#include "client/flagctl_commands.hpp"
#include "client/flagctl_link.hpp"
#include "flagsim/camera_command_t.hpp"

namespace flagsim {
namespace {

/// What the moves' arguments fill in, turned into the command when one runs.
struct CameraArguments {
  camera_command_t command{};
  double degrees = 0, degrees2 = 0;  ///< the angles as typed
  std::vector<double> point;         ///< m, X Y Z

  /// degrees => rad, the point => vector: the command to send.
  camera_command_t Command() const {
    camera_command_t ready = command;
    ready.angle = degrees * M_PI / 180;
    ready.angle2 = degrees2 * M_PI / 180;
    for (size_t k = 0; k < point.size() && k < 3; ++k) ready.vector[k] = point[k];
    return ready;
  }
};

/// The camera's subcommands; `move` sets its operation before the move is sent.
void AddMoves(CLI::App* camera, const std::shared_ptr<CameraArguments>& arguments, Invocation& invocation) {
  CameraArguments& a = *arguments;
  const auto add_move = [&](const char* name, const char* help, int8_t operation) {
    CLI::App* move = camera->add_subcommand(name, help);
    invocation.RunOnParse(move, [&invocation, arguments, operation] {
      arguments->command.operation = operation;
      return SendCommand(invocation.globals, &Channels::camera, arguments->Command());
    });
    return move;
  };
  add_move("rotate-x", "turn the scene about the x axis through the target", camera_command_t::ROTATE_X)
      ->add_option("degrees", a.degrees, "the angle in degrees, right-handed about +x")
      ->required();
  add_move("rotate-y", "turn the scene about the y (up) axis through the target", camera_command_t::ROTATE_Y)
      ->add_option("degrees", a.degrees, "the angle in degrees, right-handed about +y")
      ->required();
  add_move("rotate-z", "turn the scene about the z axis through the target", camera_command_t::ROTATE_Z)
      ->add_option("degrees", a.degrees, "the angle in degrees, right-handed about +z")
      ->required();
  CLI::App* orbit =
      add_move("orbit", "move the eye around the target; it stops at the ground rather than going under",
               camera_command_t::ORBIT);
  orbit->add_option("azimuth", a.degrees, "degrees around the vertical axis through the target")->required();
  orbit->add_option("elevation", a.degrees2, "degrees up (negative: down); the eye stops at the ground")
      ->required();
  add_move("zoom", "move the eye along the line to the target (kept 0.1 .. 200 m from it, and 0.05 m short of the flag)",
           camera_command_t::ZOOM)
      ->add_option("factor", a.command.factor,
                   "the distance is divided by it: 2 twice as close, 0.5 twice as far")
      ->required();
  add_move("translate", "move eye and target by X Y Z", camera_command_t::TRANSLATE)
      ->add_option("offset", a.point, "X Y Z in m")
      ->expected(3)
      ->required();
  add_move("look-at", "aim at the point X Y Z", camera_command_t::LOOK_AT)
      ->add_option("point", a.point, "X Y Z in m")
      ->expected(3)
      ->required();
  add_move("eye", "put the eye at X Y Z, looking at the same target", camera_command_t::SET_EYE)
      ->add_option("point", a.point, "X Y Z in m (y up, at least 0.05 above the ground)")
      ->expected(3)
      ->required();
  add_move("fov", "set the vertical field of view", camera_command_t::SET_FOV)
      ->add_option("degrees", a.degrees, "10 .. 120 degrees")
      ->required();
  CLI::App* size = add_move("size", "set the image size", camera_command_t::SET_IMAGE_SIZE);
  size->add_option("width", a.command.width, "px")->required();
  size->add_option("height", a.command.height, "px")->required();
  CLI::App* zoom_at = add_move(
      "zoom-at", "move eye and target toward what pixel X Y shows (the flag's nearest point there), stopping short of the flag",
      camera_command_t::ZOOM_AT);
  zoom_at->add_option("factor", a.command.factor, "the distance is divided by it: 2 twice as close")->required();
  zoom_at->add_option("pixel", a.point, "X Y in px from the picture's top left")->expected(2)->required();
  add_move("frame", "the flag in the middle of the picture, seen along the present line of sight",
           camera_command_t::FRAME);
  add_move("reset", "back to the scene's camera", camera_command_t::RESET);
}

/// camera scale: a zoom, or with --about a scaling of the scene about a point.
void AddScale(CLI::App* camera, const std::shared_ptr<CameraArguments>& arguments, Invocation& invocation) {
  CLI::App* scale = camera->add_subcommand(
      "scale",
      "zoom toward the target (as zoom); with --about, scale the scene about that point instead (the seed's "
      "transform)");
  scale
      ->add_option("factor", arguments->command.factor,
                   "2: twice as close, or twice the size about the point")
      ->required();
  CLI::Option* about =
      scale->add_option("--about", arguments->point, "X Y Z in m: the point to scale the scene about")
          ->expected(3);
  invocation.RunOnParse(scale, [&invocation, arguments, about] {
    arguments->command.operation = about->count() > 0 ? camera_command_t::SCALE : camera_command_t::ZOOM;
    return SendCommand(invocation.globals, &Channels::camera, arguments->Command());
  });
}

}  // namespace

void AddCameraCommand(CLI::App& app, Invocation& invocation) {
  CLI::App* camera = app.add_subcommand(
      "camera", "move the camera (angles in degrees, distances in m); the eye stays above the ground");
  camera->require_subcommand(1);
  auto arguments = std::make_shared<CameraArguments>();
  arguments->command.factor = 1;
  AddMoves(camera, arguments, invocation);
  AddScale(camera, arguments, invocation);
}

}  // namespace flagsim
