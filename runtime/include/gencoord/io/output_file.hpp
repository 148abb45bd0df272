// SPDX-License-Identifier: BSD-3-Clause
// An output file whose write failures are errors: a full disk or a vanished folder throws
// OutputError with the path instead of leaving a short file behind without a word.
#pragma once

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>

namespace gencoord {

/// Writing a file failed (it could not be opened, or a write, flush or close failed).
/// `error_number` is the errno the failure left (ENOSPC for a full disk), 0 when unknown.
class OutputError : public std::runtime_error {
 public:
  OutputError(const std::string& path, const std::string& what, int error_number = 0)
      : std::runtime_error("gencoord: " + what + " '" + path + "' failed" + cause(error_number) +
                           "; the file is incomplete"),
        path_(path),
        error_number_(error_number) {}
  const std::string& path() const { return path_; }
  int error_number() const { return error_number_; }

 private:
  static std::string cause(int error_number) {
    if (error_number == 0) return " (disk full, no permission, or the folder is gone?)";
    return std::string(": ") + std::strerror(error_number);
  }
  std::string path_;
  int error_number_;
};

/// A file opened (truncated) for writing. Writes go through stream(); check() after them,
/// flush() and close() throw OutputError naming the path when the stream has failed. Buffered
/// data reaches the file only at a flush, so a failure shows up at the flush that follows it:
/// call close() at the end and treat the file as written only when it returns.
class OutputFile {
 public:
  /// \throws OutputError if the file cannot be opened.
  explicit OutputFile(std::string path) : path_(std::move(path)) {
    errno = 0;  // so that a failure's errno is the stream's own
    out_.open(path_);
    if (!out_) throw OutputError(path_, "opening", errno);
  }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  /// Closes the file if close() was not called; a failure there is reported on stderr, since
  /// a destructor cannot throw.
  ~OutputFile() {
    if (!out_.is_open()) return;
    out_.close();
    if (!out_) std::fprintf(stderr, "gencoord: error: writing '%s' failed\n", path_.c_str());
  }

  std::ostream& stream() { return out_; }
  const std::string& path() const { return path_; }

  /// \throws OutputError if a write to the stream has failed.
  void check() const {
    if (!out_) throw OutputError(path_, "writing", errno);
  }
  /// Flushes the buffer to the file. \throws OutputError if that or an earlier write failed.
  void flush() {
    out_.flush();
    check();
  }
  /// Flushes and closes. \throws OutputError if that or an earlier write failed.
  void close() {
    if (!out_.is_open()) return;
    out_.flush();
    const bool written = static_cast<bool>(out_);
    const int flush_errno = errno;
    out_.close();
    if (!written || !out_) throw OutputError(path_, "writing", written ? errno : flush_errno);
  }
  /// Closes the file, ignoring errors, and removes it if it is a regular file (not a device
  /// such as /dev/stdout): what a failed write leaves is not a result. True if it removed it.
  bool discard() noexcept {
    out_.close();
    std::error_code ignored;
    return std::filesystem::is_regular_file(path_, ignored) &&
           std::filesystem::remove(path_, ignored);
  }

 private:
  std::string path_;
  std::ofstream out_;
};

}  // namespace gencoord
