#pragma once
// Input files read whole (mesh files): a path in a scene may name anything, a device, a FIFO or a file
// of terabytes. The file is opened once, refused unless it is a regular file within `max_bytes`, and only
// then read (or hashed) through the same descriptor, never past the limit, so that a file replaced or
// grown meanwhile cannot get around the check either.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace rift {

struct InputFileLimit {
  uint64_t max_bytes;
  std::string key;  // the scene key that raises it, for the message ("mesh.max_file_bytes"); "" for none
};

// The whole file. Throws rift::Error "<path>: cannot ... <what>" / "<what> is N bytes, above ...";
// `what` names the kind of file ("mesh file").
std::string read_input_file(const std::filesystem::path& path, const InputFileLimit& limit,
                            std::string_view what);

// FNV-1a 64 of the file's bytes, read in blocks (no copy of the whole file in memory); the same checks.
uint64_t hash_input_file(const std::filesystem::path& path, const InputFileLimit& limit,
                         std::string_view what);

}  // namespace rift
