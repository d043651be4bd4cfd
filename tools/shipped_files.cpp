// Implements shipped_files.hpp from /proc/self/exe and the relative path the build compiles in.
#include "shipped_files.hpp"

#include <filesystem>
#include <system_error>

namespace dstrans::cli {

result<std::string> shipped_files() {
  std::error_code e;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", e);
  if (e) return failure{"cannot find where the dstrans command is (/proc/self/exe: " + e.message() + ")"};
  const std::filesystem::path dir = (self.parent_path() / DSTRANS_SHIPPED_FROM_BINARY).lexically_normal();
  if (!std::filesystem::exists(dir / "report.py", e) || !std::filesystem::is_directory(dir / "scenes", e))
    return failure{dir.string() + " does not hold the files dstrans ships with (scenes/, report.py): install dstrans "
                   "whole, or run it from its build folder"};
  return dir.string();
}

}  // namespace dstrans::cli
