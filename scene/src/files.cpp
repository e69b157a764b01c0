#include <qverify/scene/files.hpp>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace qverify {

namespace {

std::string os_reason(int err) { return std::generic_category().message(err); }

[[noreturn]] void fail(const std::filesystem::path& path, int err, const std::string& reason) {
  throw FileWriteError("cannot write " + path.string() + ": " + reason, path, reason, err);
}
[[noreturn]] void fail(const std::filesystem::path& path, int err) { fail(path, err, os_reason(err)); }
[[noreturn]] void fail_directory(const std::filesystem::path& dir, const std::error_code& ec) {
  const std::string reason = ec ? ec.message() : "exists and is not a directory";
  throw FileWriteError("cannot create directory " + dir.string() + ": " + reason, dir, reason,
                       ec ? ec.value() : ENOTDIR);
}

/// Closes a descriptor once; the destructor covers the paths that throw.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
  int release_and_close() {
    const int r = ::close(fd);
    fd = -1;
    return r;
  }
  Descriptor() = default;
  Descriptor(Descriptor&& o) noexcept : fd(o.fd) { o.fd = -1; }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  Descriptor& operator=(Descriptor&&) = delete;
};

/// A fresh temporary next to `path` (same file system, so a rename is atomic), open for writing;
/// errors name `shown` (the path the user gave).
Descriptor open_temporary(const std::filesystem::path& path, std::filesystem::path& tmp,
                          const std::filesystem::path& shown) {
  const std::string base = path.filename().string();
  if (base.empty() || base == "." || base == "..") fail(shown, EINVAL, "not a file name");
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  static std::atomic<unsigned long> counter{0};
  Descriptor d;
  for (int attempt = 0; d.fd < 0; ++attempt) {
    tmp = dir / ("." + base + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    d.fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (d.fd < 0 && (errno != EEXIST || attempt > 100)) fail(shown, errno);
  }
  return d;
}

/// A temporary made at `at` and removed at once: whether its directory takes a new file (errors name
/// `shown`).
void try_temporary(const std::filesystem::path& at, const std::filesystem::path& shown) {
  std::filesystem::path tmp;
  Descriptor d = open_temporary(at, tmp, shown);
  d.release_and_close();
  ::unlink(tmp.c_str());
}

/// The file `path` names, its symbolic links followed (a link is written through, never replaced by
/// the rename: it may be someone's), checked to be a regular file or none: a device, a FIFO or a
/// socket is refused before any work, as the scene reader refuses them (the rename replaced
/// /dev/full with a PNG, audit 37b F2), and a directory too (rename(2) would say so after the work;
/// a link to a directory it replaced, the link itself). Links are followed here, not by the kernel,
/// so the kernel's rule for them (fs.protected_symlinks) is kept here: a link in a sticky
/// world-writable directory (/tmp) is followed only when its owner is this user or the directory's
/// owner (another user's /tmp/out.png -> ~/.bashrc would have had the rename replace .bashrc; review
/// of 1da4b1b). Errors name `path` as given.
std::filesystem::path regular_target(const std::filesystem::path& path) {
  std::filesystem::path p = path;
  std::error_code ec;
  for (int hops = 0;; ++hops) {
    const auto st = std::filesystem::symlink_status(p, ec);
    if (st.type() != std::filesystem::file_type::symlink) {
      switch (st.type()) {
        case std::filesystem::file_type::not_found:
        case std::filesystem::file_type::regular:
        case std::filesystem::file_type::none: return p;  // (none: status unknown; the open will say)
        case std::filesystem::file_type::directory: fail(path, EISDIR);
        default: fail(path, EINVAL, "not a regular file");
      }
    }
    if (hops == 40) fail(path, ELOOP);
    struct stat link {}, dir {};
    const std::filesystem::path parent = p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
    if (::lstat(p.c_str(), &link) != 0 || ::stat(parent.c_str(), &dir) != 0) fail(path, errno);
    if ((dir.st_mode & S_ISVTX) && (dir.st_mode & S_IWOTH) && link.st_uid != ::geteuid() && link.st_uid != dir.st_uid)
      fail(path, EACCES, "a symbolic link of another user in a sticky world-writable directory (not followed)");
    const std::filesystem::path t = std::filesystem::read_symlink(p, ec);
    if (ec) fail(path, ec.value());
    p = t.is_absolute() ? t : parent / t;
  }
}

}  // namespace

void write_file(const std::filesystem::path& path_given, std::string_view contents) {
  const std::filesystem::path path = regular_target(path_given);
  std::filesystem::path tmp;
  Descriptor d = open_temporary(path, tmp, path_given);
  auto give_up = [&](int err) {
    if (d.fd >= 0) d.release_and_close();
    ::unlink(tmp.c_str());
    fail(path_given, err);
  };

  const char* p = contents.data();
  std::size_t left = contents.size();
  while (left > 0) {
    const ssize_t n = ::write(d.fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      give_up(errno);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  // Errors the file system reports late (a full disk, a quota, NFS) surface at fsync or close.
  if (::fsync(d.fd) != 0 && errno != EINVAL && errno != EROFS) give_up(errno);
  if (d.release_and_close() != 0) give_up(errno);
  if (::rename(tmp.c_str(), path.c_str()) != 0) give_up(errno);
}

void check_writable(const std::filesystem::path& path) { try_temporary(regular_target(path), path); }

void check_output_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  const auto type = std::filesystem::status(dir, ec).type();
  if (type == std::filesystem::file_type::not_found) return check_writable(dir);  // the parent takes a new entry
  if (type != std::filesystem::file_type::directory) fail_directory(dir, ec);
  try_temporary(dir / "x", dir);  // (a temporary in it, whatever an entry named x there is)
}

void create_output_directory(const std::filesystem::path& dir) {
  if (dir.empty()) return;  // the current directory
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir, ec)) fail_directory(dir, ec);
}

}  // namespace qverify
