#include "server/scene/design_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "common/design_image.hpp"
#include "server/render/srgb.hpp"

namespace flagsim {
namespace {

/// The texture of `image`, at most DesignFile::kMaxTexels a side. Each texel is the mean of the
/// image's pixels under it (a box filter, whole and partial pixels by their area), in linear light
/// with the colour weighted by alpha, so that transparent pixels lend no colour to their
/// neighbours; the texel's colour is that mean over its alpha, back in sRGB.
render::Texture TextureOf(const RgbaImage& image) {
  const double scale = std::min(1.0, double(DesignFile::kMaxTexels) / std::max(image.width, image.height));
  render::Texture texture;
  texture.width = std::max(1, int(std::lround(image.width * scale)));
  texture.height = std::max(1, int(std::lround(image.height * scale)));
  const bool transparent = image.HasTransparency();
  texture.rgb.resize(size_t(texture.width) * texture.height * 3);
  if (transparent) texture.alpha.resize(size_t(texture.width) * texture.height);
  // Texel (tx, ty) covers image pixels [tx * sx, (tx + 1) * sx) x [ty * sy, (ty + 1) * sy).
  const double sx = double(image.width) / texture.width, sy = double(image.height) / texture.height;
  std::vector<float> linear(256);
  for (int b = 0; b < 256; ++b) linear[size_t(b)] = render::SrgbToLinear(float(b) / 255.0f);
  const auto overlap = [](double a0, double a1, int pixel) {
    return std::max(0.0, std::min(a1, double(pixel + 1)) - std::max(a0, double(pixel)));
  };
  for (int ty = 0; ty < texture.height; ++ty) {
    const double y0 = ty * sy, y1 = (ty + 1) * sy;
    for (int tx = 0; tx < texture.width; ++tx) {
      const double x0 = tx * sx, x1 = (tx + 1) * sx;
      double sum[4] = {0, 0, 0, 0}, area = 0;
      for (int y = int(y0); y < std::min(int(std::ceil(y1)), image.height); ++y) {
        const double wy = overlap(y0, y1, y);
        for (int x = int(x0); x < std::min(int(std::ceil(x1)), image.width); ++x) {
          const double w = wy * overlap(x0, x1, x);
          const uint8_t* pixel = &image.rgba[(size_t(y) * image.width + x) * 4];
          const double alpha = pixel[3] / 255.0;
          for (int k = 0; k < 3; ++k) sum[k] += w * alpha * linear[pixel[k]];
          sum[3] += w * alpha;
          area += w;
        }
      }
      const size_t texel = size_t(ty) * texture.width + tx;
      for (int k = 0; k < 3; ++k) {
        const double colour = sum[3] > 0 ? sum[k] / sum[3] : 0.0;
        texture.rgb[texel * 3 + size_t(k)] = uint8_t(std::lround(255 * render::LinearToSrgb(float(colour))));
      }
      if (transparent) texture.alpha[texel] = uint8_t(std::lround(255 * sum[3] / area));
    }
  }
  return texture;
}

}  // namespace

double DesignFile::WidthFor(double flag_height) const {
  return std::clamp(flag_height * width / height, 0.1, 10.0);  // the width parameter's range, m
}

std::string CheckDesignName(const std::string& name) {
  if (name.empty() || name.size() > DesignFile::kMaxNameLength)
    return "name: " + std::to_string(name.size()) + " characters; allowed 1 .. " +
           std::to_string(DesignFile::kMaxNameLength);
  for (const char c : name) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == '/')
      return "name: allowed printable characters without '/' (a file's name, not its path)";
  }
  return "";
}

std::string MakeDesignFile(const std::string& name, std::vector<uint8_t> bytes, DesignFilePtr* file) {
  std::string problem = CheckDesignName(name);
  if (!problem.empty()) return problem;
  RgbaImage image;
  problem = DecodeDesignImage(bytes.data(), bytes.size(), &image);
  if (!problem.empty()) return problem;
  auto made = std::make_shared<DesignFile>();
  made->name = name;
  made->digest = Sha256Hex(bytes.data(), bytes.size());
  made->bytes = std::move(bytes);
  made->width = image.width;
  made->height = image.height;
  made->texture = TextureOf(image);
  *file = std::move(made);
  return "";
}

std::string LoadDesignFile(const std::string& path, DesignFilePtr* file) {
  std::vector<uint8_t> bytes;
  const std::string unread = ReadDesignFile(path, &bytes);
  if (!unread.empty()) return unread;
  const std::string problem =
      MakeDesignFile(std::filesystem::path(path).filename().string(), std::move(bytes), file);
  return problem.empty() ? "" : path + ": " + problem;
}

}  // namespace flagsim
