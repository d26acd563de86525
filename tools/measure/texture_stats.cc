// texture-stats: the statistics msbench's textures are matched on (docs/worlds.md, "Burned
// parts"): grey mean and standard deviation, and OpenCV FAST corners (threshold 15, non-maximum
// suppression) without and after cv::equalizeHist, per square block of an image file or of one
// of msbench's procedural textures.
//
//   texture-stats FILE [BLOCK_PX]            an image (PNG, JPEG), blocks of BLOCK_PX (default 512)
//   texture-stats --procedural NAME [PX]     msbench's texture NAME rendered at PX (default 512)
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "sim/world/procedural_textures.h"

namespace {

// One block's line: position, grey mean and deviation, FAST corners raw and equalised.
void printBlock(const cv::Mat& grey, const cv::Rect& r) {
  const cv::Mat block = grey(r).clone();
  cv::Mat eq;
  cv::equalizeHist(block, eq);
  std::vector<cv::KeyPoint> raw, equalised;
  cv::FAST(block, raw, 15, true);
  cv::FAST(eq, equalised, 15, true);
  cv::Scalar mean, sd;
  cv::meanStdDev(block, mean, sd);
  std::printf("%5d %5d %5d %6.1f %6.1f %8zu %8zu\n", r.x, r.y, r.width, mean[0], sd[0], raw.size(), equalised.size());
}

int usage() {
  std::fprintf(stderr,
               "usage: texture-stats FILE [BLOCK_PX]\n"
               "       texture-stats --procedural NAME [PX]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage();
  const std::string first = argv[1];
  cv::Mat grey;
  int block = 512;
  if (first == "--procedural") {
    if (argc < 3 || !msb::isTextureName(argv[2])) return usage();
    const int px = argc > 3 ? std::atoi(argv[3]) : 512;
    grey = msb::makeTexture(argv[2], px, 0);  // the seed the world cache uses
    block = px;
  } else {
    grey = cv::imread(first, cv::IMREAD_GRAYSCALE);
    if (argc > 2) block = std::atoi(argv[2]);
  }
  if (grey.empty() || block <= 0) {
    std::fprintf(stderr, "texture-stats: cannot read '%s' (or bad block size)\n", first.c_str());
    return 1;
  }
  std::printf("    x     y  block   mean     sd  fast_raw  fast_eq\n");
  for (int y = 0; y + block <= grey.rows; y += block)
    for (int x = 0; x + block <= grey.cols; x += block) printBlock(grey, cv::Rect(x, y, block, block));
  return 0;
}
