#include "io/file_bytes.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

namespace anitet {

namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

Status io_error(const char* verb, const std::string& path, int err) {
  return Status(Error::FileNotFound,
                std::string("cannot ") + verb + " '" + path + "': " + std::strerror(err));
}

}  // namespace

Result<std::string> read_file_bytes(const std::string& path) {
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (!file) return io_error("open", path, errno);
  // Read in large chunks until EOF: works for pipes and reports directories (EISDIR).
  std::string bytes;
  struct stat info;
  if (fstat(fileno(file.get()), &info) == 0) {
    if (S_ISDIR(info.st_mode)) return io_error("read", path, EISDIR);
    if (S_ISREG(info.st_mode) && info.st_size > 0) bytes.reserve(static_cast<size_t>(info.st_size));
  }
  constexpr size_t kChunk = 1 << 20;
  std::unique_ptr<char[]> chunk(new char[kChunk]);
  for (;;) {
    size_t got = std::fread(chunk.get(), 1, kChunk, file.get());
    bytes.append(chunk.get(), got);
    if (got < kChunk) break;
  }
  if (std::ferror(file.get())) return io_error("read", path, errno ? errno : EIO);
  return bytes;
}

namespace {

using Produce = std::function<bool(const std::function<bool(std::string_view)>&)>;

Status write_directly(const std::string& path, const std::string& shown, const Produce& produce) {
  FilePtr file(std::fopen(path.c_str(), "wb"));
  if (!file) return io_error("create", shown, errno);
  int err = 0;
  const bool finished = produce([&](std::string_view bytes) {
    if (err == 0 && std::fwrite(bytes.data(), 1, bytes.size(), file.get()) != bytes.size()) err = errno ? errno : EIO;
    return err == 0;
  });
  if (err != 0) return io_error("write", shown, err);
  if (!finished) return Status(Error::Internal, "'" + shown + "': the writer stopped before the end");
  if (std::fclose(file.release()) != 0) return io_error("write", shown, errno ? errno : EIO);
  return Status::success();
}

}  // namespace

Status write_file_with(const std::string& path, const Produce& produce) {
  // A regular file is written beside its final name and renamed into place, so a failed or
  // interrupted write never leaves a truncated file that looks complete (and an old file stays
  // whole until the new one is). Devices, pipes and symbolic links (whose target a rename would
  // not replace) are written as they are.
  struct stat info;
  if (lstat(path.c_str(), &info) == 0 && !S_ISREG(info.st_mode)) return write_directly(path, path, produce);
  const std::string temp = partial_path(path);
  if (Status s = write_directly(temp, path, produce); !s.ok()) {
    std::remove(temp.c_str());
    return s;
  }
  return move_into_place(temp, path);
}

Status write_file_bytes(const std::string& path, std::string_view bytes) {
  return write_file_with(path, [bytes](const std::function<bool(std::string_view)>& write) { return write(bytes); });
}

namespace {

// Creates and removes `probe`; the error names `shown`.
Status probe_file(const std::string& probe, const std::string& shown) {
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return io_error("create", shown, errno);
  ::close(fd);
  ::unlink(probe.c_str());
  return Status::success();
}

}  // namespace

Status check_can_create(const std::string& path, bool directory) {
  if (path.empty()) return Status(Error::FileNotFound, "cannot create a file with an empty name");
  struct stat info;
  if (directory) {
    std::string dir = path;
    while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
    if (stat(dir.c_str(), &info) == 0 && !S_ISDIR(info.st_mode)) return io_error("create directory", path, ENOTDIR);
    // The nearest existing ancestor: the writer creates the rest.
    while (stat(dir.c_str(), &info) != 0) {
      if (errno != ENOENT) return io_error("create directory", path, errno);
      const size_t slash = dir.find_last_of('/');
      dir = slash == std::string::npos ? "." : slash == 0 ? "/" : dir.substr(0, slash);
    }
    if (!S_ISDIR(info.st_mode)) return io_error("create directory", path, ENOTDIR);
    return probe_file(dir + "/.anitet-probe-" + std::to_string(getpid()), path);
  }
  if (lstat(path.c_str(), &info) == 0) {
    if (S_ISDIR(info.st_mode)) return io_error("create", path, EISDIR);
    if (!S_ISREG(info.st_mode)) {  // written directly (write_file_with): it must open for writing
      const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NONBLOCK);
      // ENXIO: a FIFO no one reads yet; ENOENT: a dangling link, whose target the writer creates.
      if (fd < 0 && errno != ENXIO && errno != ENOENT) return io_error("open", path, errno);
      if (fd >= 0) ::close(fd);
      return Status::success();
    }
  }
  return probe_file(partial_path(path), path);
}

std::string partial_path(const std::string& path) { return path + ".part-" + std::to_string(getpid()); }

Status move_into_place(const std::string& partial, const std::string& path) {
  if (std::rename(partial.c_str(), path.c_str()) != 0) {
    const int err = errno;
    std::remove(partial.c_str());
    return io_error("replace", path, err);
  }
  return Status::success();
}

std::string lower_extension(const std::string& path) {
  size_t slash = path.find_last_of("/\\");
  size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace anitet
