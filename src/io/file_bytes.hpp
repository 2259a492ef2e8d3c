// Whole-file reads and writes. Readers parse from memory (fast, and tests can feed bytes
// directly); writers build the whole file in memory and write it in one call, or hand it over
// piece by piece (write_file_with: the Medit volume writer).
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "core/status.hpp"

namespace anitet {

// The bytes of a file; Error::FileNotFound when it cannot be opened or read.
Result<std::string> read_file_bytes(const std::string& path);

// Writes (replaces) a file: into PATH.part-PID, then renamed to PATH, so that PATH is never
// left half-written (devices, pipes and symbolic links are written directly).
// Error::FileNotFound when it cannot be created, written or renamed; the partial file is removed.
Status write_file_bytes(const std::string& path, std::string_view bytes);

// The same, for a file written as it is made: produce(write) calls write(bytes) for each piece
// in order (write returns false once writing failed, and drops every later piece) and returns
// whether it finished. The file appears at PATH only when it did and every write succeeded.
Status write_file_with(const std::string& path,
                       const std::function<bool(const std::function<bool(std::string_view)>&)>& produce);

// Before any work: whether a writer could create PATH, so that a long run does not end in
// "cannot write". A file: PATH.part-PID is created and removed (an existing device, pipe or
// symbolic link is opened for writing, as the writers would); PATH must not be a directory. With
// `directory` (a writer that creates PATH and its parents, e.g. an OpenFOAM polyMesh): PATH is a
// directory or does not exist, and a probe file can be created in its nearest existing ancestor.
// Error::FileNotFound with the reason.
Status check_can_create(const std::string& path, bool directory = false);

// The name a writer fills before moving it into place: PATH.part-PID.
std::string partial_path(const std::string& path);
// Renames `partial` to `path` (replacing it); on failure removes `partial` and returns
// Error::FileNotFound naming `path`.
Status move_into_place(const std::string& partial, const std::string& path);

// The extension of a path, lower case and without the dot ("" when there is none).
std::string lower_extension(const std::string& path);

}  // namespace anitet
