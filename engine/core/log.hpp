#pragma once
// Logging: one spdlog logger for the whole engine, to the console and (during a run) to a log file
// in the output folder.
#include <spdlog/spdlog.h>

#include <filesystem>

namespace rift {

void init_logging(bool verbose, bool quiet);
// Keeps the messages logged from now on until open_log_file, which writes them first: a run logs its
// set-up before it knows the input is good, and creates its output folder only after that.
void buffer_log_messages();
// Appends; replaces a previous log file. Throws rift::Error naming the file and the OS reason when it
// cannot be opened.
// A symbolic link (or anything but a regular file) at `file` is refused, never written through.
void open_log_file(const std::filesystem::path& file);
void close_log_file();

}  // namespace rift
