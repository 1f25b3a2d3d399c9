#include "common/jpeg_file.hpp"

#include <jpeglib.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace flagsim {

// rgb rows => libjpeg, compressing into memory => the bytes
std::string EncodeJpeg(const uint8_t* rgb, int width, int height, int quality) {
  jpeg_compress_struct compressor;
  jpeg_error_mgr errors;
  compressor.err = jpeg_std_error(&errors);  // errors here are programming errors: libjpeg exits
  jpeg_create_compress(&compressor);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&compressor, &buffer, &size);
  compressor.image_width = static_cast<JDIMENSION>(width);
  compressor.image_height = static_cast<JDIMENSION>(height);
  compressor.input_components = 3;
  compressor.in_color_space = JCS_RGB;
  jpeg_set_defaults(&compressor);
  jpeg_set_quality(&compressor, quality, TRUE);
  compressor.dct_method = JDCT_IFAST;
  jpeg_start_compress(&compressor, TRUE);
  while (compressor.next_scanline < compressor.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(rgb + size_t(compressor.next_scanline) * width * 3);
    jpeg_write_scanlines(&compressor, &row, 1);
  }
  jpeg_finish_compress(&compressor);
  jpeg_destroy_compress(&compressor);
  std::string jpeg(reinterpret_cast<const char*>(buffer), size);
  std::free(buffer);
  return jpeg;
}

std::string WriteJpeg(const std::string& path, int width, int height, const uint8_t* rgb, int quality) {
  const std::string jpeg = EncodeJpeg(rgb, width, height, quality);
  std::FILE* file = std::fopen(path.c_str(), "wb");  // stdio, for errno's reason
  if (file == nullptr) return "cannot open " + path + " for writing: " + std::strerror(errno);
  const bool written =
      std::fwrite(jpeg.data(), 1, jpeg.size(), file) == jpeg.size() && std::fflush(file) == 0;
  const std::string reason = written ? "" : std::strerror(errno);
  std::fclose(file);
  return written ? "" : "writing " + path + " failed: " + reason;
}

}  // namespace flagsim
