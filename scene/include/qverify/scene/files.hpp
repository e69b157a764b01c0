#pragma once
/// \file files.hpp
/// Checked file output. Every file qverify writes (the reports and plots of
/// `audit` and `stress`, the images of `render`) goes through `write_file`:
/// the contents go to a new temporary file in the target's directory, every
/// write and the close are checked, and only then is the temporary renamed
/// over the target. A reader never sees a half-written file, and a file that
/// could not be written is an error naming the path and the reason, never a
/// silent success. A symbolic link is written through (its target replaced,
/// not the link); a target that exists and is not a regular file (a
/// directory, a device such as /dev/full, a FIFO, a socket) is an error.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace qverify {

/// A file or directory that could not be written or created. `what()` is
/// "cannot write PATH: REASON" (or "cannot create directory PATH: REASON").
struct FileWriteError : std::runtime_error {
  FileWriteError(const std::string& message, std::filesystem::path path, std::string reason, int code = 0)
      : std::runtime_error(message), path(std::move(path)), reason(std::move(reason)), code(code) {}
  std::filesystem::path path;  ///< the file or directory that failed
  std::string reason;          ///< the operating system's reason, e.g. "Is a directory"
  int code;                    ///< its errno value (EISDIR; EINVAL for a path that names no file; 0 if none)
};

/// Writes `contents` to `path`: to a temporary file in the same directory
/// first (every write checked, flushed to disk, closed), then renamed over
/// `path`. Permissions are those of a new file under the process's umask.
/// Throws FileWriteError (nothing is left behind: the temporary is removed).
void write_file(const std::filesystem::path& path, std::string_view contents);

/// Creates `dir` and its missing parents; succeeds when it is already a
/// directory. Throws FileWriteError when it cannot be created or exists as
/// something else.
void create_output_directory(const std::filesystem::path& dir);

/// Checks, before any work, that `write_file(path, ...)` can succeed as far as
/// the file system can tell now: `path` (its links followed) is a regular file
/// or none, and its directory takes a new file (one is created and removed). Throws FileWriteError with
/// the reason `write_file` would give. A full disk still surfaces at the write.
void check_writable(const std::filesystem::path& path);

/// Checks, before any work, that create_output_directory(dir) and then
/// write_file into it can succeed as far as the file system can tell now,
/// without creating anything: dir is a directory that takes a new file, or
/// does not exist and its parent takes a new entry. Throws FileWriteError.
void check_output_directory(const std::filesystem::path& dir);

}  // namespace qverify
