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
  return image_from_vtk(grab->GetOutput());
}

void render_window_to_png(vtkRenderWindow* window, const std::string& path, Overwrite overwrite) {
  write_png(capture_window(window), path, overwrite);
}

}  // namespace ambisim
