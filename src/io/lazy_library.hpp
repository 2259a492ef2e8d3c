// A shared library opened when it is first needed, by its SONAME (internal header). The optional
// solver formats go through it: linked directly, libcgns and libexoIIv2c loaded their whole trees
// (HDF5, netCDF, curl...: 50 libraries, 22 ms) at every start of the tool, for the few runs that
// write those formats.
#pragma once

#include <dlfcn.h>

#include <cstring>
#include <string>

namespace anitet {

class LazyLibrary {
 public:
  explicit LazyLibrary(const char* soname) : handle_(dlopen(soname, RTLD_NOW | RTLD_LOCAL)) {
    if (!handle_) {
      const char* why = dlerror();
      error_ = std::string("cannot load ") + soname + ": " + (why ? why : "unknown error");
    }
  }
  // Never closed: the library's exit handlers (HDF5's) must find it loaded.
  LazyLibrary(const LazyLibrary&) = delete;
  LazyLibrary& operator=(const LazyLibrary&) = delete;

  // Points f at the library's function (or variable) `name`; false (and error()) when it has none.
  template <class F>
  bool bind(F& f, const char* name) {
    if (!handle_) return false;
    void* p = dlsym(handle_, name);
    if (!p) {
      if (error_.empty()) error_ = std::string("no symbol ") + name + " in the library";
      return false;
    }
    static_assert(sizeof(F) == sizeof(p), "function pointers are data pointers here (POSIX)");
    std::memcpy(&f, &p, sizeof f);
    return true;
  }
  bool ok() const { return handle_ != nullptr && error_.empty(); }
  const std::string& error() const { return error_; }

 private:
  void* handle_;
  std::string error_;
};

}  // namespace anitet
