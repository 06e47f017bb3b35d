#include <weft/io/AtomicFile.h>

#include <weft/core/Error.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace weft {

namespace fs = std::filesystem;

void writeFileAtomically(const std::string& path, const std::string& text) {
  const fs::path target = fs::absolute(path);
  const fs::path folder = target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw InputError(path, "-", "the folder does not exist");
  std::string temp = (folder / ("." + target.filename().string() + ".tmp-XXXXXX")).string();
  const int fd = ::mkstemp(temp.data());
  if (fd < 0)
    throw InputError(path, "-",
                     "cannot create a temporary file: " + std::string(std::strerror(errno)));
  auto fail = [&](const std::string& what) {
    const std::string reason = what + ": " + std::strerror(errno);
    ::close(fd);
    ::unlink(temp.c_str());
    throw InputError(path, "-", reason);
  };
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("cannot write");
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) fail("cannot flush");
  // mkstemp creates 0600: keep the replaced file's permissions, or make an ordinary document.
  struct stat existing {};
  const mode_t mode = ::stat(target.c_str(), &existing) == 0 ? (existing.st_mode & 07777) : 0644;
  if (::fchmod(fd, mode) != 0) fail("cannot set permissions");
  if (::close(fd) != 0) {
    const std::string reason = std::string("cannot close: ") + std::strerror(errno);
    ::unlink(temp.c_str());
    throw InputError(path, "-", reason);
  }
  if (::rename(temp.c_str(), target.c_str()) != 0) {
    const std::string reason = std::string("cannot replace the file: ") + std::strerror(errno);
    ::unlink(temp.c_str());
    throw InputError(path, "-", reason);
  }
}

}  // namespace weft
