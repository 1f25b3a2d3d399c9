#include "common/png_file.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

namespace flagsim {
namespace {

struct FileCloser {
  void operator()(FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<FILE, FileCloser>;

}  // namespace

std::string WritePng(const std::string& path, int width, int height, const uint8_t* rgb) {
  File file(std::fopen(path.c_str(), "wb"));
  if (!file) return "cannot open " + path + " for writing: " + std::strerror(errno);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return "libpng could not start";
  }
  if (setjmp(png_jmpbuf(png))) {  // libpng reports errors by longjmp
    png_destroy_write_struct(&png, &info);
    return "writing " + path + " failed";
  }
  png_init_io(png, file.get());
  png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y) png_write_row(png, const_cast<uint8_t*>(rgb + size_t(y) * width * 3));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return std::fflush(file.get()) == 0 ? "" : "writing " + path + " failed: " + std::strerror(errno);
}

std::string PngFramePath(const std::string& directory, int64_t index) {
  char name[32];
  std::snprintf(name, sizeof(name), "frame_%06lld.png", static_cast<long long>(index));
  return (std::filesystem::path(directory) / name).string();
}

std::string ReadPng(const std::string& path, int* width, int* height, std::vector<uint8_t>* rgb) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str()))
    return "cannot read " + path + ": " + image.message;
  // The header alone says the size: a few bytes may claim gigabytes of pixels.
  if (image.width > kMaxPngSide || image.height > kMaxPngSide) {
    const std::string size = std::to_string(image.width) + " x " + std::to_string(image.height);
    png_image_free(&image);
    return "cannot read " + path + ": " + size + " px; allowed up to " + std::to_string(kMaxPngSide) + " x " +
           std::to_string(kMaxPngSide);
  }
  image.format = PNG_FORMAT_RGB;
  rgb->resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, rgb->data(), 0, nullptr)) {
    return "cannot decode " + path + ": " + image.message;
  }
  *width = static_cast<int>(image.width);
  *height = static_cast<int>(image.height);
  return "";
}

}  // namespace flagsim
