#include "common/picture_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "common/jpeg_file.hpp"
#include "common/png_file.hpp"

namespace flagsim {

std::optional<PictureFormat> PictureFormatOf(const std::string& path, std::string* error) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".png") return PictureFormat::kPng;
  if (extension == ".jpg" || extension == ".jpeg") return PictureFormat::kJpeg;
  *error = "cannot tell the picture format from '" + path + "'; allowed NAME.png or NAME.jpg (NAME.jpeg)";
  return std::nullopt;
}

std::string WritePicture(const std::string& path, PictureFormat format, int width, int height,
                         const uint8_t* rgb) {
  return format == PictureFormat::kPng ? WritePng(path, width, height, rgb)
                                       : WriteJpeg(path, width, height, rgb);
}

}  // namespace flagsim
