// Catch2 v2 main, compiled once for every test binary. Each test process works in a temporary
// directory of its own (TMPDIR, which std::filesystem::temp_directory_path() reads): ctest runs
// test cases in parallel, and another checkout's tests may run on the same machine, so fixed
// names under /tmp would collide. The directory is removed when the process ends.
#define CATCH_CONFIG_RUNNER
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

int main(int argc, char* argv[]) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("ambisim_test_" + std::to_string(static_cast<long>(getpid())));
  fs::remove_all(dir);
  fs::create_directories(dir);
  setenv("TMPDIR", dir.c_str(), 1);
  const int result = Catch::Session().run(argc, argv);
  std::error_code ignored;
  fs::remove_all(dir, ignored);
  return result;
}
