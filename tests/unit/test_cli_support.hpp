#pragma once
// The rift binary run from a test: its exit code and what it printed.
#include <sys/wait.h>

#include <cstdio>
#include <string>
#include <vector>

namespace rift {

struct CliResult {
  int exit_code;       // 128 + the signal when it was killed by one
  std::string output;  // stdout and stderr
};

inline std::string shell_quoted(const std::string& arg) {
  std::string out = "'";
  for (char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

inline CliResult rift(const std::vector<std::string>& args) {
  std::string command = shell_quoted(RIFT_EXECUTABLE);
  for (const auto& a : args) command += " " + shell_quoted(a);
  command += " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  std::string output;
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) output.append(buffer, n);
  const int status = ::pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), output};
}

}  // namespace rift
