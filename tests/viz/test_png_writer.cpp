// PNG round trip through VTK's writer and reader; no partial files, no silent overwrite.
#include <catch2/catch.hpp>
#include <filesystem>

#include "sim/base/input_error.h"
#include "viz/png_writer.h"

TEST_CASE("png round trip keeps every pixel and the top row on top", "[png]") {
  ambisim::ImageRgb8 img(7, 5);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      auto* p = img.pixel(x, y);
      p[0] = static_cast<std::uint8_t>(x * 30);
      p[1] = static_cast<std::uint8_t>(y * 50);
      p[2] = static_cast<std::uint8_t>(x * y);
    }
  }
  const auto dir = std::filesystem::temp_directory_path() / "ambisim_test_png";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "a.png").string();
  ambisim::write_png(img, path, ambisim::Overwrite::refuse);
  const auto back = ambisim::read_png(path);
  CHECK(back.width == 7);
  CHECK(back.height == 5);
  CHECK(back.rgb == img.rgb);
  // A second write without permission to overwrite fails and leaves the file as it was.
  ambisim::ImageRgb8 other(2, 2);
  CHECK_THROWS_AS(ambisim::write_png(other, path, ambisim::Overwrite::refuse), ambisim::InputError);
  CHECK(ambisim::read_png(path).rgb == img.rgb);
  // Only the one file exists: no temporary left behind.
  CHECK(std::distance(std::filesystem::directory_iterator(dir), {}) == 1);
  std::filesystem::remove_all(dir);
}
