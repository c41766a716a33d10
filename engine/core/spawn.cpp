#include "engine/core/spawn.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <string_view>

extern char** environ;

namespace rift {

namespace {

// posix_spawn's file actions and argument array, released on every path out.
struct SpawnActions {
  posix_spawn_file_actions_t actions{};
  bool ok = posix_spawn_file_actions_init(&actions) == 0;
  ~SpawnActions() {
    if (ok) posix_spawn_file_actions_destroy(&actions);
  }
};

}  // namespace

int run_program(const std::vector<std::string>& argv, const std::filesystem::path& cwd,
                const std::filesystem::path& log) {
  if (argv.empty()) return -1;
  SpawnActions fa;
  if (!fa.ok) return -1;
  const std::string out = log.empty() ? std::string("/dev/null") : log.string();
  // The log is opened relative to the caller's folder, before the child changes folder.
  const std::string log_abs = log.empty() ? out : std::filesystem::absolute(log).string();
  if (posix_spawn_file_actions_addopen(&fa.actions, 0, "/dev/null", O_RDONLY, 0) != 0 ||
      posix_spawn_file_actions_addopen(&fa.actions, 1, log_abs.c_str(),
                                       O_WRONLY | O_CREAT | O_APPEND | O_NOFOLLOW, 0644) != 0 ||
      posix_spawn_file_actions_adddup2(&fa.actions, 1, 2) != 0)
    return -1;
  if (!cwd.empty() && posix_spawn_file_actions_addchdir_np(&fa.actions, cwd.c_str()) != 0) return -1;
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, args[0], &fa.actions, nullptr, args.data(), environ) != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string python_with(const std::string& modules) {
  for (const char* py : {"python3", "/usr/bin/python3"})
    if (run_program({py, "-c", "import " + modules}) == 0) return py;
  return "";
}

std::string find_program(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string_view dirs = path ? path : "";
  std::string candidates;
  for (size_t start = 0; start <= dirs.size();) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string dir(dirs.substr(start, end - start));
    const std::string file = (dir.empty() ? std::string(".") : dir) + "/" + name;
    if (::access(file.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(file)) return file;
    start = end + 1;
  }
  const std::string fallback = "/usr/bin/" + name;
  return ::access(fallback.c_str(), X_OK) == 0 ? fallback : std::string();
}

}  // namespace rift
