#include "steady/core/output_file.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "steady/core/errors.hpp"

namespace steady {

void check_output_path(const std::string& path) {
  if (path.empty() || path.find('\0') != std::string::npos)
    fail_input("path", "a file path must be non-empty and must not contain a NUL character");
}

PartialFile::PartialFile(std::string path, bool open) : path_(std::move(path)) {
  check_output_path(path_);
  temporary_ = path_ + ".partial";
  if (!open) return;
  file_ = std::fopen(temporary_.c_str(), "wb");
  if (!file_) fail_input("path", "cannot write '" + path_ + "': " + std::strerror(errno));
}

PartialFile::~PartialFile() {
  if (file_) std::fclose(file_);
  if (!committed_) std::remove(temporary_.c_str());
}

void PartialFile::write(const void* data, std::size_t bytes) {
  if (bytes && std::fwrite(data, 1, bytes, file_) != bytes)
    throw std::runtime_error("writing '" + path_ + "' failed: " + std::strerror(errno));
}

void PartialFile::commit() {
  if (file_) {
    const bool flushed = std::fflush(file_) == 0;
    const bool closed = std::fclose(file_) == 0;
    file_ = nullptr;
    if (!flushed || !closed) throw std::runtime_error("writing '" + path_ + "' failed: " + std::strerror(errno));
  }
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0)
    throw std::runtime_error("cannot move the finished file into '" + path_ + "': " + std::strerror(errno));
  committed_ = true;
}

}  // namespace steady
