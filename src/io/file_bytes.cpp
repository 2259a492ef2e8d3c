#include "io/file_bytes.hpp"

#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

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

Status write_file_bytes(const std::string& path, std::string_view bytes) {
  FilePtr file(std::fopen(path.c_str(), "wb"));
  if (!file) return io_error("create", path, errno);
  if (std::fwrite(bytes.data(), 1, bytes.size(), file.get()) != bytes.size()) {
    return io_error("write", path, errno ? errno : EIO);
  }
  if (std::fclose(file.release()) != 0) return io_error("write", path, errno ? errno : EIO);
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
