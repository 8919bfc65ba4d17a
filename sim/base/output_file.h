#pragma once
// Writing outputs without ever leaving a partial file or clobbering a user's data: every file
// is written to a temporary name beside its destination and renamed into place at the end.
#include <functional>
#include <string>

namespace ambisim {

enum class Overwrite { refuse, allow };

// Throws InputError (naming `path`) if the file exists and `overwrite` is refuse, or if the
// directory is missing or not writable.
void check_output_path(const std::string& path, Overwrite overwrite);

// Calls `write(tmp_path)` to produce the file under a temporary name in the same directory,
// then renames it to `path`. On any exception the temporary file is removed and the exception
// propagates; `path` is untouched.
void write_atomically(const std::string& path, Overwrite overwrite,
                      const std::function<void(const std::string& tmp_path)>& write);

// Convenience: atomically write a whole string.
void write_text_atomically(const std::string& path, const std::string& text, Overwrite overwrite);

}  // namespace ambisim
