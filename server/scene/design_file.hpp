// A person's own image as the flag's design: the file as it came (a scene file's `design =
// "flag.png"`, or `flagctl design FILE` over the bus in pieces), checked and decoded once, and
// the texture the renderer samples. Immutable once made: scenes, checkpoints and frames share it.
//
//   file bytes => limits, decode (common/design_image.hpp) => box-filtered down to at most
//   kMaxTexels a side, in linear light with premultiplied alpha => the flag's texture
//
// The flag's width follows the image's aspect (ServiceSettings::width_follows_design) unless a
// width was set; the texture's transparent texels cut the flag's outline.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "server/render/pattern.hpp"

namespace flagsim {

struct DesignFile {
  static constexpr int kMaxTexels = 1536;        ///< the texture's longer side, at most
  static constexpr size_t kMaxNameLength = 128;  ///< characters of its name

  std::string name;            ///< the file's name as given (no folders): what the user sees
  std::string digest;          ///< SHA-256 of bytes, hex: its identity on the wire and in logs
  std::vector<uint8_t> bytes;  ///< the PNG or JPEG as it came
  int width = 0, height = 0;   ///< px of the image
  render::Texture texture;     ///< what the flag shows: RGB, and alpha if any texel is not opaque

  /// The flag's width for `height` m, by the image's aspect, within the width parameter's range.
  double WidthFor(double flag_height) const;
};

using DesignFilePtr = std::shared_ptr<const DesignFile>;

/// "" if `name` may name a design file: 1 .. kMaxNameLength printable characters, no '/'; else
/// what is wrong.
std::string CheckDesignName(const std::string& name);

/// Checks and decodes `bytes` (common/design_image.hpp) named `name`; "" and `*file`, or what
/// is wrong with it (the limits named), then `*file` is untouched.
std::string MakeDesignFile(const std::string& name, std::vector<uint8_t> bytes, DesignFilePtr* file);

/// The file at `path`, read (refused before reading if larger than the limit) and made.
std::string LoadDesignFile(const std::string& path, DesignFilePtr* file);

}  // namespace flagsim
