// Procedural, tileable grey-scale textures for the worlds. Each is feature-rich the way the real
// surface is (corners from bricks, windows, leaves, cracks), made from our own seeded RNG so the
// same name and seed always give the same bytes.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace msb {

/// Names of the available texture patterns.
const std::vector<std::string>& textureNames();

/// True if `name` is a known pattern.
bool isTextureName(const std::string& name);

/// Tile size in metres at which the pattern is applied (e.g. 2 m for bricks).
double textureTileMeters(const std::string& name);

/// Renders the named pattern as a tileable `size_px` × `size_px` CV_8UC1 image. Throws
/// std::invalid_argument for an unknown name.
cv::Mat makeTexture(const std::string& name, int size_px, uint64_t seed);

}  // namespace msb
