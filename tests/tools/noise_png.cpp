// noise_png WIDTH HEIGHT OUT.png: an RGBA PNG of random pixels (seeded, the same each run), its
// right quarter transparent. Noise does not compress: a file of about 4 bytes a pixel, for the
// tests that send a large design image.
#include <png.h>

#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: noise_png WIDTH HEIGHT OUT.png\n");
    return 2;
  }
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = png_uint_32(std::atoi(argv[1]));
  image.height = png_uint_32(std::atoi(argv[2]));
  image.format = PNG_FORMAT_RGBA;
  if (image.width < 1 || image.height < 1 || image.width > 4096 || image.height > 4096) {
    std::fprintf(stderr, "noise_png: WIDTH and HEIGHT 1 .. 4096\n");
    return 2;
  }
  std::mt19937 random(7);
  std::vector<png_byte> rgba(PNG_IMAGE_SIZE(image));
  for (size_t i = 0; i < rgba.size(); ++i) {
    const size_t x = (i / 4) % image.width;
    rgba[i] = i % 4 == 3 ? (4 * x < 3 * image.width ? 255 : 0) : png_byte(random());
  }
  if (!png_image_write_to_file(&image, argv[3], 0, rgba.data(), 0, nullptr)) {
    std::fprintf(stderr, "noise_png: %s\n", image.message);
    return 1;
  }
  return 0;
}
