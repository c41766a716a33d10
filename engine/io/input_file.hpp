#pragma once
// Input files named by a scene (scene and mesh files): a path in a scene may name anything, a device, a
// FIFO or a file of terabytes. The file is opened once, refused unless it is a regular file within
// `max_bytes`, and only then read (whole, as a stream, or hashed) through the same descriptor, never past
// the limit, so that a file replaced or grown meanwhile cannot get around the check either.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace rift {

struct InputFileLimit {
  uint64_t max_bytes;
  std::string key;  // the scene key that raises it, for the message ("mesh.max_file_bytes"); "" for none
};

// An open input file, checked as above, read in pieces (the MSH reader streams through it).
class InputFileReader {
 public:
  // Throws rift::Error "<path>: cannot open the <what>: ..." / "the <what> is N bytes, above ...";
  // `what` names the kind of file ("mesh file").
  InputFileReader(const std::filesystem::path& path, const InputFileLimit& limit, std::string_view what);
  InputFileReader(const InputFileReader&) = delete;
  InputFileReader& operator=(const InputFileReader&) = delete;
  ~InputFileReader();

  uint64_t size() const { return size_; }  // as the file was when opened
  // Up to `n` bytes into `out`; 0 at the end of the file. Throws when reading fails or the file has
  // grown past the limit since it was opened.
  size_t read_some(char* out, size_t n);

 private:
  [[noreturn]] void fail(const std::string& what);

  std::filesystem::path path_;
  std::string what_;
  int fd_ = -1;
  uint64_t size_ = 0, max_ = 0, total_ = 0;
};

// The whole file. Throws rift::Error "<path>: cannot ... <what>" / "<what> is N bytes, above ...";
// `what` names the kind of file ("mesh file").
std::string read_input_file(const std::filesystem::path& path, const InputFileLimit& limit,
                            std::string_view what);

// FNV-1a 64 of the file's bytes, read in blocks (no copy of the whole file in memory); the same checks.
uint64_t hash_input_file(const std::filesystem::path& path, const InputFileLimit& limit,
                         std::string_view what);

}  // namespace rift
