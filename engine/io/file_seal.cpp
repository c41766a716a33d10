#include "engine/io/file_seal.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/fnv1a.hpp"

namespace rift {
namespace {

constexpr const char* kSealFormat = "rift-seal fnv1a64 %16s bytes %" SCNu64 "\n";

// Closes the descriptor on every path out.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& file, int err) {
  throw Error(what + " '" + file.string() + "': " + std::strerror(err));
}

// FNV-1a 64 and length of the bytes after the seal block, read in 1 MiB pieces.
std::pair<uint64_t, uint64_t> hash_after_block(int fd, const std::filesystem::path& file) {
  std::vector<char> buffer(1 << 20);
  uint64_t h = fnv1a64_basis, bytes = 0;
  for (off_t at = kSealBytes;;) {
    const ssize_t n = ::pread(fd, buffer.data(), buffer.size(), at);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("cannot read", file, errno);
    }
    if (n == 0) break;
    h = fnv1a64(buffer.data(), static_cast<size_t>(n), h);
    bytes += static_cast<uint64_t>(n);
    at += n;
  }
  return {h, bytes};
}

}  // namespace

void seal_file(const std::filesystem::path& file) {
  const Fd f{::open(file.c_str(), O_RDWR | O_NOFOLLOW | O_CLOEXEC)};
  if (f.fd < 0) fail("cannot open to seal", file, errno);
  const auto [h, bytes] = hash_after_block(f.fd, file);
  std::array<char, kSealBytes> block{};
  std::snprintf(block.data(), block.size(), "rift-seal fnv1a64 %s bytes %" PRIu64 "\n", hex16(h).c_str(),
                bytes);
  if (::pwrite(f.fd, block.data(), block.size(), 0) != static_cast<ssize_t>(block.size()))
    fail("cannot write the seal of", file, errno);
}

void check_file_seal(const std::filesystem::path& file, const std::string& damaged) {
  const Fd f{::open(file.c_str(), O_RDONLY | O_CLOEXEC)};
  if (f.fd < 0) fail("cannot open", file, errno);
  std::array<char, kSealBytes + 1> block{};
  const ssize_t got = ::pread(f.fd, block.data(), kSealBytes, 0);
  char stored[17] = {};
  uint64_t stored_bytes = 0;
  if (got != static_cast<ssize_t>(kSealBytes) ||
      std::sscanf(block.data(), kSealFormat, stored, &stored_bytes) != 2)
    throw Error(damaged +
                "it does not start with its seal (the whole-file checksum Rift writes in its first " +
                std::to_string(kSealBytes) + " bytes)");
  const auto [h, bytes] = hash_after_block(f.fd, file);
  if (bytes != stored_bytes || hex16(h) != stored)
    throw Error(damaged + "its bytes do not match its seal (sealed " + std::to_string(stored_bytes) +
                " bytes with FNV-1a 64 " + stored + ", found " + std::to_string(bytes) + " bytes with " +
                hex16(h) + ")");
}

}  // namespace rift
