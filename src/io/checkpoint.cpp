#include "io/checkpoint.hpp"

#include <fmt/format.h>

#include <cstring>
#include <filesystem>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace gf::io {

namespace {
constexpr char kMagic[16] = {'G', 'R', 'A', 'I', 'N', 'F', 'L', 'O', 'W', '-', 'C', 'K', 'P', 'T', 0, 0};
}

void writeCheckpoint(const std::string& path, std::uint64_t caseFingerprint, const BinaryWriter& payload) {
  const std::vector<char>& body = payload.bytes();
  BinaryWriter file;
  for (char c : kMagic) file.put(c);
  file.put<std::uint32_t>(kCheckpointVersion);
  file.put<std::uint64_t>(caseFingerprint);
  file.put<std::uint64_t>(body.size());
  std::string bytes(file.bytes().begin(), file.bytes().end());
  bytes.append(body.begin(), body.end());
  const std::uint64_t checksum = fnv1a(body.data(), body.size());
  bytes.append(reinterpret_cast<const char*>(&checksum), sizeof(checksum));
  writeFileAtomically(path, bytes);
}

std::vector<char> readCheckpoint(const std::string& path, std::uint64_t expectedCaseFingerprint) {
  if (!std::filesystem::exists(path)) throw CheckpointError(fmt::format("checkpoint '{}': no such file", path));
  const std::string bytes = readFile(path);
  const std::size_t headerSize = sizeof(kMagic) + 4 + 8 + 8;
  if (bytes.size() < headerSize || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
    throw CheckpointError(fmt::format("checkpoint '{}' is not a grainflow checkpoint (bad magic)", path));
  BinaryReader header(bytes.data() + sizeof(kMagic), headerSize - sizeof(kMagic));
  const auto version = header.get<std::uint32_t>();
  const auto fingerprint = header.get<std::uint64_t>();
  const auto payloadSize = header.get<std::uint64_t>();
  if (version != kCheckpointVersion)
    throw CheckpointError(fmt::format("checkpoint '{}' has format version {}, this grainflow reads version {}", path,
                                      version, kCheckpointVersion));
  if (payloadSize + headerSize + 8 != bytes.size())
    throw CheckpointError(fmt::format("checkpoint '{}' is truncated or corrupt: {} bytes, header announces {}", path,
                                      bytes.size(), payloadSize + headerSize + 8));
  std::uint64_t checksum = 0;
  std::memcpy(&checksum, bytes.data() + headerSize + payloadSize, 8);
  if (checksum != fnv1a(bytes.data() + headerSize, payloadSize))
    throw CheckpointError(fmt::format("checkpoint '{}' is corrupt: checksum mismatch", path));
  if (fingerprint != expectedCaseFingerprint)
    throw CheckpointError(fmt::format(
        "checkpoint '{}' was written for another case (fingerprint {:016x}, this case has {:016x}); only keys "
        "under output, checkpoint, monitors, run and time.end may change between a run and its restart",
        path, fingerprint, expectedCaseFingerprint));
  return std::vector<char>(bytes.begin() + headerSize, bytes.begin() + headerSize + payloadSize);
}

}  // namespace gf::io
