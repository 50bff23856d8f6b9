#include "core/error.hpp"

#include <fmt/format.h>

namespace gf {

std::string FileLocation::str() const {
  if (line <= 0) return file;
  if (column <= 0) return fmt::format("{}:{}", file, line);
  return fmt::format("{}:{}:{}", file, line, column);
}

CaseError::CaseError(FileLocation where, std::string keyPath, std::string found, std::string expected)
    : Error(fmt::format("{}: error: key '{}': found {}, expected {}", where.str(), keyPath, found, expected)),
      where_(std::move(where)),
      keyPath_(std::move(keyPath)) {}

DivergenceError::DivergenceError(long long step, double time, std::string quantity, std::string where,
                                 Vec3 position, std::string detail)
    : Error(fmt::format("run diverged at step {} (t = {:.6g} s): {} in {} at position ({:.6g}, {:.6g}, {:.6g}) m: {}",
                        step, time, quantity, where, position.x, position.y, position.z, detail)),
      step_(step) {}

}  // namespace gf
