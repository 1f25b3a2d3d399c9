// The live view's page, built from web/ by the project's build and embedded in flagctl, so
// `flagctl serve` needs no files beside it and the page no internet.
#pragma once

#include <string_view>

namespace flagsim::gateway {

struct WebAsset {
  std::string_view content_type;
  std::string_view body;
};

/// The asset served at `path` ("/" is index.html); nullptr if none.
const WebAsset* FindWebAsset(std::string_view path);

}  // namespace flagsim::gateway
