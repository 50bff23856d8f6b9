#pragma once
// Error types. Every error a user can cause says where (file, line, column, key),
// what was found and what was expected; every divergence names step, quantity and place.
#include <stdexcept>
#include <string>

#include "core/vec3.hpp"

namespace gf {

/// Base of all grainflow errors; what() is the complete user-facing message.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A position in a case file (1-based line and column; 0 = unknown).
struct FileLocation {
  std::string file;
  int line = 0;
  int column = 0;
  std::string str() const;  // "case.yaml:12:5" (or just the file)
};

/// Invalid input in a case file: bad type, range, unknown key or model, inconsistent geometry.
class CaseError : public Error {
 public:
  CaseError(FileLocation where, std::string keyPath, std::string found, std::string expected);
  const FileLocation& where() const { return where_; }
  const std::string& keyPath() const { return keyPath_; }

 private:
  FileLocation where_;
  std::string keyPath_;
};

/// A run that went unstable: NaN/Inf, particle leaving the domain, CFL blow-up.
class DivergenceError : public Error {
 public:
  DivergenceError(long long step, double time, std::string quantity, std::string where, Vec3 position,
                  std::string detail);
  /// The same error with its message already written (one rank's error passed on to the others).
  DivergenceError(long long step, const std::string& message) : Error(message), step_(step) {}
  long long step() const { return step_; }

 private:
  long long step_;
};

/// Problems with checkpoint files (corrupt, truncated, from another case or version).
class CheckpointError : public Error {
 public:
  using Error::Error;
};

}  // namespace gf
