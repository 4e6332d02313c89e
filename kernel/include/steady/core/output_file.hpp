#pragma once
// Files are written under a temporary name beside their final one and renamed into place once complete, so an
// error, a full disk or a cancel never leaves a partial file under the final name (and never spoils an older one).
#include <cstdio>
#include <string>

namespace steady {

// InvalidInput ("path") for an empty path or one containing a NUL character.
void check_output_path(const std::string& path);

class PartialFile {
 public:
  // Checks the path; with `open`, opens the temporary file for binary writing (InvalidInput naming the path and
  // the reason when it cannot). Without, a writer that opens files itself (a library) writes to temporary_path().
  explicit PartialFile(std::string path, bool open = true);
  PartialFile(const PartialFile&) = delete;
  PartialFile& operator=(const PartialFile&) = delete;
  ~PartialFile();  // removes the temporary file unless committed

  const std::string& temporary_path() const { return temporary_; }
  std::FILE* file() { return file_; }
  // Throws std::runtime_error naming the path when the bytes cannot all be written.
  void write(const void* data, std::size_t bytes);
  void write(const std::string& text) { write(text.data(), text.size()); }
  // Flushes, closes and renames the file into place (std::runtime_error when any of it fails).
  void commit();

 private:
  std::string path_, temporary_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

}  // namespace steady
