#include "server/render/pattern.hpp"

namespace flagsim::render {
namespace {

struct Rgb {
  uint8_t r, g, b;
};

Rgb DesignColour(FlagDesign design, float u, float v) {
  switch (design) {
    case FlagDesign::kNordicCross: {
      const bool vertical_bar = u >= 0.30f && u < 0.42f, horizontal_bar = v >= 0.40f && v < 0.60f;
      return vertical_bar || horizontal_bar ? Rgb{250, 204, 20} : Rgb{0, 82, 165};
    }
    case FlagDesign::kTricolour:
      return u < 1.0f / 3 ? Rgb{0, 122, 61} : u < 2.0f / 3 ? Rgb{245, 245, 240} : Rgb{206, 17, 38};
    case FlagDesign::kChecker:
      return (int(u * 8) + int(v * 8)) % 2 == 0 ? Rgb{230, 230, 230} : Rgb{40, 40, 40};
    case FlagDesign::kImage:
      break;
  }
  return Rgb{255, 255, 255};
}

}  // namespace

Texture MakePattern(FlagDesign design, int width, int height) {
  Texture texture;
  texture.width = width;
  texture.height = height;
  texture.rgb.resize(size_t(width) * height * 3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const Rgb colour = DesignColour(design, (x + 0.5f) / width, (y + 0.5f) / height);
      uint8_t* texel = &texture.rgb[(size_t(y) * width + x) * 3];
      texel[0] = colour.r;
      texel[1] = colour.g;
      texel[2] = colour.b;
    }
  }
  return texture;
}

}  // namespace flagsim::render
