#include "sim/base/output_file.h"

#include <atomic>
#include <filesystem>
#include <fstream>
#include <system_error>

#include <unistd.h>

#include "sim/base/input_error.h"

namespace ambisim {
namespace fs = std::filesystem;

void check_output_path(const std::string& path, Overwrite overwrite) {
  std::error_code ec;
  const fs::path p(path);
  const auto status = fs::status(p, ec);
  if (fs::exists(status)) {
    if (fs::is_directory(status)) throw InputError(path, "", "is a directory");
    if (overwrite == Overwrite::refuse) {
      throw InputError(path, "", "already exists (use --force to overwrite)");
    }
  }
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec)) throw InputError(path, "", "directory does not exist");
  if (::access(dir.c_str(), W_OK) != 0) throw InputError(path, "", "directory is not writable");
}

void write_atomically(const std::string& path, Overwrite overwrite,
                      const std::function<void(const std::string& tmp_path)>& write) {
  check_output_path(path, overwrite);
  static std::atomic<unsigned> counter{0};
  const std::string tmp =
      path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter.fetch_add(1));
  try {
    write(tmp);
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) throw InputError(path, "", "cannot rename into place: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

void write_text_atomically(const std::string& path, const std::string& text, Overwrite overwrite) {
  write_atomically(path, overwrite, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw InputError(path, "", "write failed");
  });
}

}  // namespace ambisim
