#pragma once
// Starting helper programs (the sweep's plotter) from an argument vector, never through a shell, so
// that no scene name, path or value can be read as a command.
#include <filesystem>
#include <string>
#include <vector>

namespace rift {

// Runs argv[0] (looked up on PATH when it has no '/') with the arguments argv[1..], in working folder
// `cwd` (unchanged when empty), with standard input from /dev/null and standard output and error
// appended to `log` (discarded when empty). Waits for it and returns its exit status; -1 when it could
// not be started or did not exit normally.
int run_program(const std::vector<std::string>& argv, const std::filesystem::path& cwd = {},
                const std::filesystem::path& log = {});

// The path of the executable `name` on PATH, else in /usr/bin; empty when there is none.
std::string find_program(const std::string& name);

// The first Python that imports `modules` (e.g. "matplotlib"): the one on PATH, else Debian's
// /usr/bin/python3 (pyenv or a venv may shadow it). Empty when neither does.
std::string python_with(const std::string& modules);

}  // namespace rift
