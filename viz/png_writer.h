#pragma once
// PNG output of 8-bit images through VTK's PNG writer (atomic: never a partial file).
#include <string>

#include "sim/base/image.h"
#include "sim/base/output_file.h"

class vtkImageData;

namespace ambisim {

// A VTK image (bottom row first, 1-4 components) as an 8-bit RGB raster, top row first.
ImageRgb8 image_from_vtk(vtkImageData* data);

void write_png(const ImageRgb8& image, const std::string& path, Overwrite overwrite);

// Reads a PNG back (used by tests to check what was written).
ImageRgb8 read_png(const std::string& path);

}  // namespace ambisim
