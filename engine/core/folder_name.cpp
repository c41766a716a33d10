#include "engine/core/folder_name.hpp"

namespace rift {

std::string safe_folder_name(const std::string& name) {
  std::string out;
  for (unsigned char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '-' || c == '_' || c == '.';
    out += keep ? char(c) : '_';
  }
  if (out.empty() || out == "." || out == "..") return "scene";
  return out;
}

}  // namespace rift
