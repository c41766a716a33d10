#pragma once
// Logging: one spdlog logger for the whole engine, to the console and (during a run) to a log file
// in the output folder.
#include <filesystem>

#include <spdlog/spdlog.h>

namespace rift {

void init_logging(bool verbose, bool quiet);
void open_log_file(const std::filesystem::path& file);  // appends; replaces a previous log file
void close_log_file();

}  // namespace rift
