#include "core/util/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "core/util/temporary_files.h"

namespace handlab::util {
namespace {

namespace fs = std::filesystem;

// A stream buffer over a file descriptor it does not own.
class DescriptorBuffer : public std::streambuf {
 public:
  explicit DescriptorBuffer(int fd) : fd_(fd) {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }
  ~DescriptorBuffer() override { sync(); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (sync() != 0) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override {
    const char* at = pbase();
    while (at < pptr()) {
      const ssize_t n = ::write(fd_, at, std::size_t(pptr() - at));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        error_ = n < 0 ? errno : EIO;
        setp(buffer_.data(), buffer_.data() + buffer_.size());
        return -1;
      }
      at += n;
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return 0;
  }

 private:
  int fd_;
  int error_ = 0;
  std::array<char, 1 << 16> buffer_;
};

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw OutputError("cannot write " + path + ": " + why);
}

std::string system_reason(int error) {
  return std::strerror(error);
}

// Streams `write` into `fd`; throws with the reason if any byte did not arrive.
void stream_to(int fd, const std::string& path, const std::function<void(std::ostream&)>& write) {
  DescriptorBuffer buffer(fd);
  std::ostream out(&buffer);
  write(out);
  out.flush();
  if (!out || buffer.error() != 0)
    refuse(path, system_reason(buffer.error() != 0 ? buffer.error() : EIO));
}

// The descriptor a path names when it is one of this process' own (/dev/stdout, /dev/fd/2,
// /proc/self/fd/3): writing there means writing to that descriptor, never replacing the file
// behind it, which the shell may have opened for appending.
std::optional<int> own_descriptor(const std::string& path) {
  static const std::array<std::pair<const char*, int>, 3> named = {
      {{"/dev/stdout", 1}, {"/dev/stderr", 2}, {"/dev/stdin", 0}}};
  for (const auto& [name, fd] : named)
    if (path == name) return fd;
  for (const std::string prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    if (path.rfind(prefix, 0) != 0) continue;
    const std::string number = path.substr(prefix.size());
    if (number.empty() || number.size() > 9 ||
        number.find_first_not_of("0123456789") != std::string::npos)
      continue;
    return std::stoi(number);
  }
  return std::nullopt;
}

// Follows symbolic links to the path they end at (which need not exist yet).
std::string follow_links(const std::string& path) {
  fs::path at = path;
  for (int hops = 0; hops < 40; ++hops) {
    if (own_descriptor(at.string())) return at.string();
    struct stat link {};
    if (::lstat(at.c_str(), &link) != 0 || !S_ISLNK(link.st_mode)) return at.string();
    std::error_code error;
    const fs::path target = fs::read_symlink(at, error);
    if (error) refuse(path, error.message());
    at = target.is_absolute() ? target : at.parent_path() / target;
  }
  refuse(path, "too many levels of symbolic links");
}

void write_through(const std::string& target, const std::string& path,
                   const std::function<void(std::ostream&)>& write) {
  const int fd = ::open(target.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) refuse(path, system_reason(errno));
  try {
    stream_to(fd, path, write);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
}

// Makes the temporary file beside `target`, with the signals held until its name is
// registered: a signal in between cannot leave it behind. Created 0666 under the umask, as
// any new file, close-on-exec.
std::unique_ptr<TemporaryFile> make_temporary(const std::string& target, const std::string& path,
                                              int* fd) {
  static std::atomic<unsigned> made{0};
  prepare_temporary_files();
  const SignalsHeld held;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::string name =
        target + ".part-" + std::to_string(::getpid()) + "-" + std::to_string(made++);
    *fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (*fd >= 0) return std::make_unique<TemporaryFile>(name);
    if (errno != EEXIST) refuse(path, system_reason(errno));
  }
  refuse(path, "no free name for a temporary file beside it");
}

void replace_file(const std::string& target, const std::string& path, const struct stat* existing,
                  const std::function<void(std::ostream&)>& write) {
  const fs::path folder = fs::path(target).parent_path();
  struct stat folder_stat {};
  if (!folder.empty()) {
    if (::stat(folder.c_str(), &folder_stat) != 0)
      refuse(path, errno == ENOENT ? "the folder " + folder.string() + " does not exist"
                                   : "the folder " + folder.string() + ": " + system_reason(errno));
    if (!S_ISDIR(folder_stat.st_mode)) refuse(path, folder.string() + " is not a folder");
  }
  int fd = -1;
  const std::unique_ptr<TemporaryFile> temporary = make_temporary(target, path, &fd);
  try {
    if (existing) ::fchmod(fd, existing->st_mode & 07777);  // a replaced file keeps its mode
    stream_to(fd, path, write);
    if (::fsync(fd) != 0) refuse(path, system_reason(errno));
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) refuse(path, system_reason(errno));
  if (::rename(temporary->path().c_str(), target.c_str()) != 0) refuse(path, system_reason(errno));
  temporary->keep();
}

}  // namespace

void write_output(const std::string& path, const std::function<void(std::ostream&)>& write) {
  if (path.empty()) throw OutputError("cannot write to an empty path");
  if (path == "-") {
    write(std::cout);
    if (!std::cout.flush()) refuse("standard output", "it was closed");
    return;
  }
  const std::string target = follow_links(path);
  if (const auto fd = own_descriptor(target)) {
    if (*fd == 1) {
      write(std::cout);
      if (!std::cout.flush()) refuse(path, "standard output was closed");
      return;
    }
    std::cout.flush();
    return stream_to(*fd, path, write);
  }
  struct stat st {};
  if (::stat(target.c_str(), &st) != 0) {
    if (errno != ENOENT) refuse(path, system_reason(errno));
    return replace_file(target, path, nullptr, write);
  }
  if (S_ISREG(st.st_mode)) return replace_file(target, path, &st, write);
  if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return write_through(target, path, write);
  if (S_ISDIR(st.st_mode)) refuse(path, "it is a folder (name a file in it)");
  if (S_ISBLK(st.st_mode))
    refuse(path, "it is a block device (a disk), which handlab never writes to");
  refuse(path, "it is a socket or another special file, which handlab does not write to");
}

bool is_stream_output(const std::string& path) {
  if (path == "-") return true;
  const std::string target = follow_links(path);
  if (own_descriptor(target)) return true;
  struct stat st {};
  return ::stat(target.c_str(), &st) == 0 && (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode));
}

void make_output_folder(const std::string& path) {
  if (path.empty()) throw OutputError("name a folder for the outputs");
  fs::path at;
  for (const fs::path& part : fs::path(path)) {
    at /= part;
    struct stat st {};
    if (::stat(at.c_str(), &st) == 0) {
      if (!S_ISDIR(st.st_mode))
        throw OutputError("cannot write into " + path + ": " + at.string() +
                          " is a file, not a folder (name a folder)");
      continue;
    }
    if (::mkdir(at.c_str(), 0777) != 0 && errno != EEXIST)
      throw OutputError("cannot make the folder " + at.string() + ": " + system_reason(errno));
  }
}

void write_output_bytes(const std::string& path, std::string_view bytes) {
  write_output(path,
               [&](std::ostream& out) { out.write(bytes.data(), std::streamsize(bytes.size())); });
}

}  // namespace handlab::util
