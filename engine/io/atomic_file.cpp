#include "engine/io/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <string>

#include "engine/core/error.hpp"

namespace rift {
namespace {

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path, int err) {
  throw Error(what + " '" + path.string() + "': " + std::strerror(err));
}

// fsync through a fresh descriptor: Linux flushes the file's dirty pages regardless of which
// descriptor wrote them, so this also covers files written by HDF5 or an ofstream.
void fsync_path(const std::filesystem::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) fail("cannot open for fsync", path, errno);
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    // Some file systems (e.g. certain network mounts) refuse fsync on directories; the data is
    // still written, only the durability guarantee is weaker.
    if ((flags & O_DIRECTORY) && (err == EINVAL || err == EBADF)) return;
    fail("cannot fsync", path, err);
  }
  ::close(fd);
}

// Fault injection for the crash tests (tests/slow/test_faults.cpp, docs/reliability.md): with
// RIFT_FAULT_KILL_AT_COMMIT=<n> in the environment the process kills itself with SIGKILL at its n-th
// commit, the temp file written and synced, the rename not done: the moment a crash hurts most.
void kill_here_if_asked() {
  static const long kill_at = [] {
    const char* value = std::getenv("RIFT_FAULT_KILL_AT_COMMIT");
    return value ? std::strtol(value, nullptr, 10) : 0L;
  }();
  static std::atomic<long> commits{0};
  if (kill_at > 0 && ++commits == kill_at) ::raise(SIGKILL);
}

}  // namespace

AtomicPath::AtomicPath(std::filesystem::path target)
    : target_(std::move(target)), temp_(temp_for(target_, ::getpid())) {
  // A failure here (e.g. a read-only folder) surfaces when the writer creates the file.
  ::unlink(temp_.c_str());
}

int AtomicPath::create_temp() const {
  const int fd = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) fail("cannot create", temp_, errno);
  return fd;
}

AtomicPath::~AtomicPath() {
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove(temp_, ignored);
  }
}

void AtomicPath::commit() {
  if (committed_) return;
  fsync_path(temp_, O_RDONLY | O_NOFOLLOW);
  kill_here_if_asked();
  if (::rename(temp_.c_str(), target_.c_str()) != 0)
    throw Error("cannot rename '" + temp_.string() + "' to '" + target_.string() +
                "': " + std::strerror(errno));
  committed_ = true;
  std::filesystem::path dir = target_.parent_path();
  if (dir.empty()) dir = ".";
  fsync_path(dir, O_RDONLY | O_DIRECTORY);
}

bool AtomicPath::is_temp_name(const std::filesystem::path& path) {
  const std::string name = path.filename().string();
  const auto at = name.rfind(".tmp-");
  if (at == std::string::npos || at + 5 == name.size()) return false;
  for (size_t i = at + 5; i < name.size(); ++i)
    if (name[i] < '0' || name[i] > '9') return false;
  return true;
}

std::filesystem::path AtomicPath::temp_for(const std::filesystem::path& target, pid_t pid) {
  std::filesystem::path temp = target;
  temp += ".tmp-" + std::to_string(pid);
  return temp;
}

std::optional<AtomicPath::TempName> AtomicPath::parse_temp_name(std::string_view name) {
  const size_t at = name.rfind(".tmp-");
  if (at == std::string_view::npos || at == 0) return std::nullopt;
  const char* first = name.data() + at + 5;
  const char* last = name.data() + name.size();
  pid_t pid = 0;
  const auto [end, ec] = std::from_chars(first, last, pid);
  if (ec != std::errc() || end != last || pid <= 0) return std::nullopt;
  TempName parsed{std::string(name.substr(0, at)), pid};
  if (temp_for(parsed.target, pid) != name) return std::nullopt;  // "+1", "01"
  return parsed;
}

bool AtomicPath::writer_is_gone(pid_t pid) {
  return pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH;
}

void write_text_atomic(const std::filesystem::path& path, std::string_view text) {
  AtomicPath atomic(path);
  const int fd = atomic.create_temp();
  const char* p = text.data();
  size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      fail("cannot write", atomic.temp(), err);
    }
    p += n;
    left -= static_cast<size_t>(n);
  }
  if (::close(fd) != 0) fail("cannot close", atomic.temp(), errno);
  atomic.commit();
}

}  // namespace rift
