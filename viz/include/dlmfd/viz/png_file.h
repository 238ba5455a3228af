// PNG output of a RasterImage via libpng (8-bit RGB, no interlacing). The file is written to a
// temporary name beside the target and renamed, so a reader never sees a half-written picture
// (design.md 3.2). Throws dlmfd::Error with the path and libpng's message on failure.
#pragma once

#include <string>

#include "dlmfd/viz/raster_image.h"

namespace dlmfd {

void WritePng(const RasterImage& image, const std::string& path);

}  // namespace dlmfd
