#pragma once
// Default output folders named after scenes.
#include <string>

namespace rift {

// A scene name as a single folder name: letters, digits, '-', '_' and '.' kept, anything else
// (separators, quotes, spaces, control characters) replaced by '_'; "", "." and ".." become "scene".
// The default output folder rift-out/<name> therefore always lies inside rift-out/.
std::string safe_folder_name(const std::string& name);

}  // namespace rift
