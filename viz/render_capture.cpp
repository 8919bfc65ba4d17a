#include "viz/render_capture.h"

#include <cstring>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkWindowToImageFilter.h>

#include "viz/png_writer.h"

namespace ambisim {

ImageRgb8 capture_window(vtkRenderWindow* window) {
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkImageData* data = grab->GetOutput();
  int dims[3];
  data->GetDimensions(dims);
  const int comps = data->GetNumberOfScalarComponents();
  ImageRgb8 out(dims[0], dims[1]);
  const auto* src = static_cast<const unsigned char*>(data->GetScalarPointer());
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      const unsigned char* s =
          src + (static_cast<std::size_t>(out.height - 1 - y) * out.width + x) * comps;
      std::uint8_t* d = out.pixel(x, y);
      for (int c = 0; c < 3; ++c) d[c] = s[comps >= 3 ? c : 0];
    }
  }
  return out;
}

void render_window_to_png(vtkRenderWindow* window, const std::string& path, Overwrite overwrite) {
  write_png(capture_window(window), path, overwrite);
}

}  // namespace ambisim
