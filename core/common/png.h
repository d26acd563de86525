// PNG encoding through libpng (Debian's libpng-dev): the pictures msbench writes (top-down maps,
// annotated frames, world textures). Lossless and deterministic: the same pixels give the same
// bytes. Kept out of OpenCV's imgcodecs, whose closure is ~140 shared libraries.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace msb {

/// An 8-bit image in memory: rows of `width` pixels of `channels` bytes (1 grey, 3 BGR, 4 BGRA, as
/// OpenCV stores them), `stride` bytes apart.
struct ImageView {
  const uint8_t* data = nullptr;
  int width = 0, height = 0, channels = 0;
  size_t stride = 0;
};

/// The view of an 8-bit OpenCV matrix (or anything with its data, cols, rows, channels(), step).
template <class Mat>
ImageView viewOf(const Mat& m) {
  return {m.data, m.cols, m.rows, m.channels(), static_cast<size_t>(m.step)};
}

/// The PNG bytes of `image` (zlib level 6), with a text chunk "Software: msbench" that marks the
/// file as msbench's (isMsbenchPng). Throws std::runtime_error on an invalid view or a libpng
/// failure.
std::string encodePng(const ImageView& image);

/// True if `bytes` are a PNG that encodePng wrote (its "Software: msbench" chunk before the
/// pixels): only such a file may be replaced by an msbench output.
bool isMsbenchPng(const std::string& bytes);

/// Writes `image` as a PNG file (not atomically: callers stage their outputs). Throws
/// std::runtime_error naming the file when it cannot be written.
void writePng(const std::filesystem::path& file, const ImageView& image);

}  // namespace msb
