#include "engine/io/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/fnv1a.hpp"

namespace rift {
InputFileReader::InputFileReader(const std::filesystem::path& path, const InputFileLimit& limit,
                                 std::string_view what)
    : path_(path), what_(what), max_(limit.max_bytes) {
  // O_NONBLOCK: opening a FIFO would otherwise wait for a writer; it is refused just below.
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) fail("cannot open the " + what_ + ": " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd_, &st) != 0) fail("cannot inspect the " + what_ + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) fail("the " + what_ + " is not a regular file");
  size_ = static_cast<uint64_t>(st.st_size);
  if (size_ > max_)
    fail("the " + what_ + " is " + std::to_string(size_) + " bytes, above the limit of " +
         std::to_string(max_) + " bytes" + (limit.key.empty() ? "" : " (raise it with " + limit.key + ")"));
}

InputFileReader::~InputFileReader() {
  if (fd_ >= 0) ::close(fd_);
}

size_t InputFileReader::read_some(char* out, size_t n) {
  for (;;) {
    const ssize_t got = ::read(fd_, out, n);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) fail("cannot read the " + what_ + ": " + std::strerror(errno));
    total_ += static_cast<uint64_t>(got);
    if (total_ > max_) fail("the " + what_ + " grew beyond the limit of " + std::to_string(max_) + " bytes");
    return static_cast<size_t>(got);
  }
}

// Closes the descriptor before throwing: a constructor that throws runs no destructor.
void InputFileReader::fail(const std::string& what) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  throw Error(path_.string() + ": " + what);
}

std::string read_input_file(const std::filesystem::path& path, const InputFileLimit& limit,
                            std::string_view what) {
  InputFileReader in(path, limit, what);
  std::string text(static_cast<size_t>(in.size()), '\0');
  size_t used = 0;
  for (;;) {
    if (used == text.size()) text.resize(used + 64 * 1024);  // grown since fstat: read on to the limit
    const size_t got = in.read_some(text.data() + used, text.size() - used);
    if (got == 0) break;
    used += got;
  }
  text.resize(used);
  return text;
}

uint64_t hash_input_file(const std::filesystem::path& path, const InputFileLimit& limit,
                         std::string_view what) {
  InputFileReader in(path, limit, what);
  std::vector<char> block(1 << 20);
  uint64_t h = fnv1a64_basis;
  for (size_t got; (got = in.read_some(block.data(), block.size())) > 0;) h = fnv1a64(block.data(), got, h);
  return h;
}

}  // namespace rift
