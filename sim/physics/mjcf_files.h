// The files a world's MJCF reads as XML: the world file and every file it `<include>`s,
// recursively (MuJoCo resolves an include's path against the world file's directory). Each is
// checked like the world file — it exists, is a regular file (a FIFO or device never blocks the
// loader), is at most 64 MiB and not empty — and read here, so MuJoCo compiles from memory and
// opens none of them itself. Errors name the world, the file and the reason (ConfigError "world").
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace msb {

/// (path, content) of the world file, then of each included file in the order first included;
/// at most 256 files, no file twice (a cycle is refused). Throws ConfigError.
std::vector<std::pair<std::string, std::string>> readMjcfFiles(const std::string& world_xml_path);

/// The paths readMjcfFiles reads (for the outputs-never-overlap-inputs check).
std::vector<std::string> mjcfInputFiles(const std::string& world_xml_path);

}  // namespace msb
