#pragma once
// Versioned binary checkpoints with checksum and case fingerprint, written atomically.
//
// Layout: magic "GRAINFLOW-CKPT\0\0" (16 bytes) | uint32 format version | uint64 case fingerprint |
//         uint64 payload size | payload | uint64 FNV-1a checksum of the payload.
// The payload is whatever the solver parts write through BinaryWriter, in a fixed order.
#include <cstdint>
#include <string>
#include <vector>

#include "core/serialize.hpp"

namespace gf::io {

inline constexpr std::uint32_t kCheckpointVersion = 1;

void writeCheckpoint(const std::string& path, std::uint64_t caseFingerprint, const BinaryWriter& payload);

/// Reads and verifies a checkpoint; returns its payload. Throws CheckpointError when the file is
/// missing, truncated, corrupt (checksum), of another format version, or from another case.
std::vector<char> readCheckpoint(const std::string& path, std::uint64_t expectedCaseFingerprint);

}  // namespace gf::io
