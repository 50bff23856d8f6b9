#pragma once
// Crash-safe file writes: everything is written to a temporary file in the same directory and
// renamed over the target, so a crash never leaves a half-written output or checkpoint.
#include <string>
#include <string_view>

namespace gf::io {

/// Writes `content` to `path` atomically (temp file + fsync + rename). Throws gf::Error on failure.
void writeFileAtomically(const std::string& path, std::string_view content);

/// Reads a whole file; throws gf::Error naming the file if it cannot be read.
std::string readFile(const std::string& path);

}  // namespace gf::io
