#include "viz/png_writer.h"

#include <cstring>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include "sim/base/input_error.h"

namespace ambisim {

ImageRgb8 image_from_vtk(vtkImageData* data) {
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

void write_png(const ImageRgb8& image, const std::string& path, Overwrite overwrite) {
  vtkNew<vtkImageData> data;
  data->SetDimensions(image.width, image.height, 1);
  data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* dst = static_cast<unsigned char*>(data->GetScalarPointer());
  // VTK images start at the bottom row; ours start at the top.
  const std::size_t row = static_cast<std::size_t>(image.width) * 3;
  for (int y = 0; y < image.height; ++y) {
    std::memcpy(dst + static_cast<std::size_t>(image.height - 1 - y) * row,
                image.rgb.data() + static_cast<std::size_t>(y) * row, row);
  }
  write_atomically(path, overwrite, [&](const std::string& tmp) {
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(tmp.c_str());
    writer->SetInputData(data);
    writer->Write();
    if (writer->GetErrorCode() != 0) throw InputError(path, "", "PNG write failed");
  });
}

ImageRgb8 read_png(const std::string& path) {
  vtkNew<vtkPNGReader> reader;
  if (reader->CanReadFile(path.c_str()) == 0) throw InputError(path, "", "not a readable PNG");
  reader->SetFileName(path.c_str());
  reader->Update();
  return image_from_vtk(reader->GetOutput());
}

}  // namespace ambisim
