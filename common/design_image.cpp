#include "common/design_image.hpp"

#include <jpeglib.h>
#include <openssl/evp.h>
#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace flagsim {
namespace {

std::string Size(int64_t width, int64_t height) {
  return std::to_string(width) + " x " + std::to_string(height) + " px";
}

/// "" if width x height px are within the limits, else what is wrong and what is allowed.
std::string CheckPixels(int64_t width, int64_t height) {
  if (width <= 0 || height <= 0) return "the image is " + Size(width, height) + ": it has no pixels";
  if (width > kMaxDesignSide || height > kMaxDesignSide || width * height > kMaxDesignPixels)
    return "the image is " + Size(width, height) + "; allowed: " + DesignLimits();
  return "";
}

bool IsPng(const uint8_t* data, size_t size) { return size >= 8 && png_sig_cmp(data, 0, 8) == 0; }
bool IsJpeg(const uint8_t* data, size_t size) {
  return size >= 3 && data[0] == 0xff && data[1] == 0xd8 && data[2] == 0xff;
}

// ---- PNG: libpng's simplified API, which reports errors in image.message, no longjmp to us.

std::string PngHeader(const uint8_t* data, size_t size, png_image* image) {
  *image = png_image{};
  image->version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(image, data, size))
    return std::string("the PNG's header cannot be read: ") + image->message;
  return "";
}

std::string DecodePng(const uint8_t* data, size_t size, RgbaImage* out) {
  png_image image;
  std::string problem = PngHeader(data, size, &image);
  if (problem.empty()) problem = CheckPixels(image.width, image.height);
  if (!problem.empty()) {
    png_image_free(&image);
    return problem;
  }
  image.format = PNG_FORMAT_RGBA;
  std::vector<uint8_t> rgba(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, rgba.data(), 0, nullptr))
    return std::string("the PNG cannot be decoded: ") + image.message;
  *out = {int(image.width), int(image.height), std::move(rgba)};
  return "";
}

// ---- JPEG: libjpeg reports errors through error_exit, which must not return: it longjmps back
// here. Between setjmp and the jump only the C structures live, and each entry point below
// cleans up after itself. A warning (a damaged or truncated stream, which libjpeg would fill
// with grey) is an error too: a bad file changes nothing.

struct JpegErrors {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

void JpegErrorExit(j_common_ptr info) {
  auto* errors = reinterpret_cast<JpegErrors*>(info->err);
  (*info->err->format_message)(info, errors->message);
  std::longjmp(errors->jump, 1);
}

void JpegWarning(j_common_ptr info, int level) {
  if (level < 0) JpegErrorExit(info);  // -1: a warning; higher levels are trace messages
}

/// Reads the header and, if `rgba`, the pixels (the header's size checked first).
std::string ReadJpeg(const uint8_t* data, size_t size, int* width, int* height, std::vector<uint8_t>* rgba) {
  jpeg_decompress_struct reader;
  JpegErrors errors;
  reader.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = JpegErrorExit;
  errors.manager.emit_message = JpegWarning;
  if (setjmp(errors.jump)) {
    jpeg_destroy_decompress(&reader);
    return std::string("the JPEG cannot be decoded: ") + errors.message;
  }
  jpeg_create_decompress(&reader);
  jpeg_mem_src(&reader, data, static_cast<unsigned long>(size));
  jpeg_read_header(&reader, TRUE);
  *width = int(reader.image_width);
  *height = int(reader.image_height);
  const std::string problem = CheckPixels(reader.image_width, reader.image_height);
  if (!problem.empty() || rgba == nullptr) {
    jpeg_destroy_decompress(&reader);
    return problem;
  }
  reader.out_color_space = JCS_EXT_RGBA;  // libjpeg-turbo: alpha filled opaque
  jpeg_start_decompress(&reader);
  rgba->resize(size_t(*width) * size_t(*height) * 4);
  while (reader.output_scanline < reader.output_height) {
    JSAMPROW row = rgba->data() + size_t(reader.output_scanline) * size_t(*width) * 4;
    jpeg_read_scanlines(&reader, &row, 1);
  }
  jpeg_finish_decompress(&reader);
  jpeg_destroy_decompress(&reader);
  return "";
}

}  // namespace

std::string DesignLimits() {
  return "a PNG or JPEG file of 1 byte .. " + std::to_string(kMaxDesignFileBytes >> 20) + " MiB, 1 .. " +
         std::to_string(kMaxDesignSide) + " px a side and at most " + std::to_string(kMaxDesignPixels >> 20) +
         " Mpx";
}

std::string InspectDesignImage(const uint8_t* data, size_t size, ImageHeader* header) {
  if (size == 0) return "the file is empty; allowed: " + DesignLimits();
  if (size > kMaxDesignFileBytes)
    return "the file is " + std::to_string(size) + " bytes; allowed: " + DesignLimits();
  if (IsPng(data, size)) {
    png_image image;
    std::string problem = PngHeader(data, size, &image);
    if (problem.empty()) problem = CheckPixels(image.width, image.height);
    png_image_free(&image);
    if (!problem.empty()) return problem;
    *header = {ImageFormat::kPng, int(image.width), int(image.height)};
    return "";
  }
  if (IsJpeg(data, size)) {
    int width = 0, height = 0;
    const std::string problem = ReadJpeg(data, size, &width, &height, nullptr);
    if (!problem.empty()) return problem;
    *header = {ImageFormat::kJpeg, width, height};
    return "";
  }
  return "the file is neither a PNG nor a JPEG (by its first bytes); allowed: " + DesignLimits();
}

std::string DecodeDesignImage(const uint8_t* data, size_t size, RgbaImage* image) {
  ImageHeader header;
  std::string problem = InspectDesignImage(data, size, &header);
  if (!problem.empty()) return problem;
  RgbaImage decoded;
  problem = header.format == ImageFormat::kPng
                ? DecodePng(data, size, &decoded)
                : ReadJpeg(data, size, &decoded.width, &decoded.height, &decoded.rgba);
  if (problem.empty()) *image = std::move(decoded);
  return problem;
}

bool RgbaImage::HasTransparency() const {
  for (size_t i = 3; i < rgba.size(); i += 4) {
    if (rgba[i] != 255) return true;
  }
  return false;
}

std::string ReadDesignFile(const std::string& path, std::vector<uint8_t>* bytes) {
  std::error_code error;
  const uintmax_t size = std::filesystem::file_size(path, error);
  if (error) return "cannot read " + path + ": " + error.message();
  if (size > kMaxDesignFileBytes)
    return path + ": the file is " + std::to_string(size) + " bytes; allowed: " + DesignLimits();
  std::ifstream in(path, std::ios::binary);
  bytes->resize(size);
  if (!in.read(reinterpret_cast<char*>(bytes->data()), std::streamsize(size))) return "cannot read " + path;
  return "";
}

std::string Sha256Hex(const uint8_t* data, size_t size) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (EVP_Digest(data, size, digest, &length, EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("SHA-256 failed");
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) {
    hex += kHex[digest[i] >> 4];
    hex += kHex[digest[i] & 15];
  }
  return hex;
}

}  // namespace flagsim
