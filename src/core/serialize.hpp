#pragma once
// Binary (de)serialisation for checkpoints: little-endian raw values with a running checksum.
// Each subsystem writes its state through BinaryWriter and reads it back through BinaryReader
// in the same order; the checkpoint container (io/checkpoint) adds header, version and checksum.
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.hpp"

namespace gf {

/// 64-bit FNV-1a hash, used as checkpoint checksum and case fingerprint.
inline std::uint64_t fnv1a(const void* data, std::size_t size, std::uint64_t hash = 1469598103934665603ULL) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 1099511628211ULL;
  }
  return hash;
}

class BinaryWriter {
 public:
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    append(&value, sizeof(T));
  }
  template <class T>
  void putVector(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<std::uint64_t>(values.size());
    append(values.data(), values.size() * sizeof(T));
  }
  void putString(const std::string& s) {
    put<std::uint64_t>(s.size());
    append(s.data(), s.size());
  }
  const std::vector<char>& bytes() const { return bytes_; }

 private:
  void append(const void* p, std::size_t n) {
    const auto* c = static_cast<const char*>(p);
    bytes_.insert(bytes_.end(), c, c + n);
  }
  std::vector<char> bytes_;
};

class BinaryReader {
 public:
  BinaryReader(const char* data, std::size_t size) : data_(data), size_(size) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    take(&value, sizeof(T));
    return value;
  }
  template <class T>
  std::vector<T> getVector() {
    const auto n = get<std::uint64_t>();
    if (n > (size_ - pos_) / (sizeof(T) ? sizeof(T) : 1)) throw CheckpointError("checkpoint is truncated or corrupt (array length out of range)");
    std::vector<T> values(n);
    take(values.data(), n * sizeof(T));
    return values;
  }
  std::string getString() {
    const auto n = get<std::uint64_t>();
    if (n > size_ - pos_) throw CheckpointError("checkpoint is truncated or corrupt (string length out of range)");
    std::string s(n, '\0');
    take(s.data(), n);
    return s;
  }
  bool atEnd() const { return pos_ == size_; }

 private:
  void take(void* out, std::size_t n) {
    if (n > size_ - pos_) throw CheckpointError("checkpoint is truncated (ran past its end while reading)");
    if (n == 0) return;  // an empty vector's data() may be null, and memcpy(nullptr, ..., 0) is UB
    std::memcpy(out, data_ + pos_, n);
    pos_ += n;
  }
  const char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace gf
