#pragma once
// Grabbing an offscreen VTK render window into an 8-bit image and a PNG (atomic writes).
#include <string>

#include "sim/base/image.h"
#include "sim/base/output_file.h"

class vtkRenderWindow;

namespace ambisim {

// Renders the window and reads its pixels back (top row first).
ImageRgb8 capture_window(vtkRenderWindow* window);

// capture_window + write_png.
void render_window_to_png(vtkRenderWindow* window, const std::string& path, Overwrite overwrite);

}  // namespace ambisim
