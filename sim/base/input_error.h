#pragma once
// The one error type for bad user input: it names the file and the JSON path (RFC 6901
// pointer) so the message reads "motorway.json: /camera/speed_mps: must be > 0, got -3".
// The CLI turns it into exit code 2.
#include <stdexcept>
#include <string>

namespace ambisim {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string json_path, const std::string& message)
      : std::runtime_error(format(file, json_path, message)),
        file_(std::move(file)),
        path_(std::move(json_path)) {}
  const std::string& file() const { return file_; }
  const std::string& json_path() const { return path_; }

 private:
  static std::string format(const std::string& file, const std::string& path,
                            const std::string& message) {
    std::string s = file.empty() ? std::string("<input>") : file;
    s += ": ";
    if (!path.empty()) s += path + ": ";
    return s + message;
  }
  std::string file_;
  std::string path_;
};

}  // namespace ambisim
