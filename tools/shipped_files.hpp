// Where the dstrans command finds the files it ships with (the benchmark's scenes and bench/report.py):
// at a path relative to its own binary that the build compiles in (bin/ to share/dstrans/ when installed;
// the build folder keeps the same layout), never in the source tree.
#pragma once

#include <string>

#include <dstrans/result.hpp>

namespace dstrans::cli {

// The folder that holds scenes/ and report.py, or why there is none.
result<std::string> shipped_files();

}  // namespace dstrans::cli
