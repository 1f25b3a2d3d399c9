// flagd render: the command line's side of an offline render (service/offline_render.hpp):
// the log file, the PNG frames, the progress bar and the summary.
#pragma once

#include <atomic>
#include <string>

#include "server/scene/scene.hpp"

namespace flagsim {

struct RenderRequest {
  std::string log_path;  ///< the LCM log to write; "" for none
  std::string png_dir;   ///< where frame_%06d.png go; "" for none
  double duration = 0;   ///< s of simulated time
  std::string prefix;    ///< of the logged channels
};

/// Renders `scene` as `request` says until done or `stop`. Returns the exit code: 0 done,
/// 1 a file could not be written or the render was interrupted (what is written stays valid).
int RunRender(const Scene& scene, const RenderRequest& request, const std::atomic<bool>& stop);

}  // namespace flagsim
