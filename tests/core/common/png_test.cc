// PNG encoding: the bytes decode (by libpng's reader) to the pixels given, in OpenCV's channel
// order, the same pixels give the same bytes, and an invalid view is refused.
#include "core/common/png.h"

#include <png.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <gtest/gtest.h>

namespace msb {
namespace {

// Decodes PNG bytes to 8-bit pixels of `format` (libpng's simplified API).
std::vector<uint8_t> decode(const std::string& bytes, png_uint_32 format, int* width, int* height) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) throw std::runtime_error(image.message);
  image.format = format;
  std::vector<uint8_t> pixels(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) throw std::runtime_error(image.message);
  *width = static_cast<int>(image.width), *height = static_cast<int>(image.height);
  return pixels;
}

TEST(Png, BgrPixelsRoundTripThroughLibpngsReader) {
  // 5 x 3 pixels with a padded stride of 16 bytes: pixel (x, y) = (b, g, r) = (x, y, 200 + x).
  const int w = 5, h = 3;
  std::vector<uint8_t> data(16 * h, 0xEE);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      data[16 * y + 3 * x + 0] = uint8_t(x), data[16 * y + 3 * x + 1] = uint8_t(y),
                            data[16 * y + 3 * x + 2] = uint8_t(200 + x);
    }
  const ImageView view{data.data(), w, h, 3, 16};
  const std::string png = encodePng(view);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(encodePng(view), png);  // deterministic
  int dw = 0, dh = 0;
  const auto rgb = decode(png, PNG_FORMAT_RGB, &dw, &dh);
  ASSERT_EQ(dw, w);
  ASSERT_EQ(dh, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      EXPECT_EQ(rgb[3 * (w * y + x) + 0], 200 + x);  // red was stored last (BGR)
      EXPECT_EQ(rgb[3 * (w * y + x) + 1], y);
      EXPECT_EQ(rgb[3 * (w * y + x) + 2], x);
    }
}

TEST(Png, MsbenchsPngsCarryTheirMarkerAndOthersDoNot) {
  const uint8_t px[4] = {0, 64, 128, 255};
  const std::string ours = encodePng(ImageView{px, 2, 2, 1, 2});
  EXPECT_TRUE(isMsbenchPng(ours));
  std::string stripped = ours;
  stripped.replace(stripped.find("msbench"), 7, "someone");  // another program's Software chunk
  EXPECT_FALSE(isMsbenchPng(stripped));
  EXPECT_FALSE(isMsbenchPng(std::string("\x89PNG\r\n\x1a\n", 8)));
  EXPECT_FALSE(isMsbenchPng("msbench"));
}

TEST(Png, GreyImagesAndFilesAndInvalidViews) {
  const std::vector<uint8_t> grey = {0, 64, 128, 255};
  const ImageView view{grey.data(), 2, 2, 1, 2};
  int w = 0, h = 0;
  EXPECT_EQ(decode(encodePng(view), PNG_FORMAT_GRAY, &w, &h), grey);
  const auto file = std::filesystem::temp_directory_path() / "msb_png_test.png";
  writePng(file, view);
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bytes, encodePng(view));
  std::filesystem::remove(file);
  EXPECT_THROW(encodePng(ImageView{grey.data(), 2, 2, 2, 4}), std::runtime_error);  // 2 channels
  EXPECT_THROW(encodePng(ImageView{grey.data(), 4, 2, 1, 2}), std::runtime_error);  // stride too short
  EXPECT_THROW(encodePng(ImageView{}), std::runtime_error);
  EXPECT_THROW(writePng("/nonexistent-dir/x.png", view), std::runtime_error);
}

}  // namespace
}  // namespace msb
