#include "core/common/png.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace msb {

namespace {

// libpng reports an error by longjmp-ing back to the setjmp in encodePng(), which then throws;
// the message is kept in the error pointer's string.
void onPngError(png_structp png, png_const_charp message) {
  *static_cast<std::string*>(png_get_error_ptr(png)) = message;
  png_longjmp(png, 1);
}
void onPngWarning(png_structp, png_const_charp) {}

void appendBytes(png_structp png, png_bytep data, png_size_t length) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), length);
}

void flushNothing(png_structp) {}

// The libpng colour type of an OpenCV-ordered channel count.
int colourType(int channels) {
  switch (channels) {
    case 1:
      return PNG_COLOR_TYPE_GRAY;
    case 3:
      return PNG_COLOR_TYPE_RGB;
    case 4:
      return PNG_COLOR_TYPE_RGB_ALPHA;
  }
  throw std::runtime_error("PNG: " + std::to_string(channels) + " channels (1, 3 or 4 expected)");
}

}  // namespace

std::string encodePng(const ImageView& image) {
  if (!image.data || image.width <= 0 || image.height <= 0 ||
      image.stride < static_cast<size_t>(image.width) * static_cast<size_t>(image.channels))
    throw std::runtime_error("PNG: invalid image");
  const int colour = colourType(image.channels);
  std::string out;
  std::string error;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, onPngError, onPngWarning);
  if (!png) throw std::runtime_error("PNG: out of memory");
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("PNG: " + (error.empty() ? std::string("out of memory") : error));
  }
  png_set_write_fn(png, &out, appendBytes, flushNothing);
  png_set_compression_level(png, 6);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8, colour,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_text text{};
  text.compression = PNG_TEXT_COMPRESSION_NONE;
  text.key = const_cast<char*>("Software");
  text.text = const_cast<char*>("msbench");
  png_set_text(png, info, &text, 1);
  png_write_info(png, info);
  if (image.channels >= 3) png_set_bgr(png);  // OpenCV's order
  for (int y = 0; y < image.height; ++y)
    png_write_row(png, const_cast<png_bytep>(image.data + static_cast<size_t>(y) * image.stride));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

bool isMsbenchPng(const std::string& bytes) {
  static const std::string kSignature = "\x89PNG\r\n\x1a\n", kChunk = std::string("tEXtSoftware\0msbench", 20);
  const size_t idat = bytes.find("IDAT");
  const size_t text = bytes.find(kChunk);
  return bytes.compare(0, kSignature.size(), kSignature) == 0 && text != std::string::npos && text < idat;
}

void writePng(const std::filesystem::path& file, const ImageView& image) {
  const std::string bytes = encodePng(image);
  std::FILE* f = std::fopen(file.c_str(), "wb");
  if (!f) throw std::runtime_error(file.string() + ": cannot be written");
  const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error(file.string() + ": cannot be written");
}

}  // namespace msb
