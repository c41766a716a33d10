#include "engine/core/log.hpp"

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/dist_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>

namespace rift {

namespace {
std::shared_ptr<spdlog::sinks::dist_sink_mt> sinks;
std::shared_ptr<spdlog::sinks::sink> file_sink;
}  // namespace

void init_logging(bool verbose, bool quiet) {
  if (!sinks) {
    sinks = std::make_shared<spdlog::sinks::dist_sink_mt>();
    auto console = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
    console->set_pattern("%^[%l]%$ %v");
    sinks->add_sink(console);
    auto logger = std::make_shared<spdlog::logger>("rift", sinks);
    spdlog::set_default_logger(logger);
  }
  spdlog::set_level(quiet ? spdlog::level::warn : verbose ? spdlog::level::debug : spdlog::level::info);
}

void open_log_file(const std::filesystem::path& file) {
  if (!sinks) init_logging(false, false);
  close_log_file();
  file_sink = std::make_shared<spdlog::sinks::basic_file_sink_mt>(file.string(), false);
  file_sink->set_pattern("[%Y-%m-%d %H:%M:%S.%e] [%l] %v");
  file_sink->set_level(spdlog::level::debug);
  sinks->add_sink(file_sink);
}

void close_log_file() {
  if (sinks && file_sink) {
    file_sink->flush();
    sinks->remove_sink(file_sink);
    file_sink.reset();
  }
}

}  // namespace rift
