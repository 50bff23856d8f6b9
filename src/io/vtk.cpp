#include "io/vtk.hpp"

#include <fmt/format.h>

#include <cstring>
#include <filesystem>
#include <regex>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace gf::io {

namespace {
constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// Appends the base64 (RFC 4648) of the byte stream `first` (nFirst bytes) then `second`
/// (nSecond bytes) to out, written in place: the output is sized once and filled through a
/// pointer, 4 characters per 3 bytes (appending character by character, with a copy of the whole
/// array and of the encoded text per DataArray, took 1.8 us per particle for a .vtu file).
void appendBase64(std::string& out, const unsigned char* first, std::size_t nFirst, const unsigned char* second,
                  std::size_t nSecond) {
  const std::size_t total = nFirst + nSecond;
  const std::size_t start = out.size();
  out.resize(start + (total + 2) / 3 * 4);
  char* o = out.data() + start;
  auto emit = [&o](std::uint32_t v) {  // 24 bits -> 4 characters
    o[0] = kAlphabet[(v >> 18) & 63];
    o[1] = kAlphabet[(v >> 12) & 63];
    o[2] = kAlphabet[(v >> 6) & 63];
    o[3] = kAlphabet[v & 63];
    o += 4;
  };
  auto byteAt = [&](std::size_t k) -> std::uint32_t { return k < nFirst ? first[k] : second[k - nFirst]; };
  std::size_t k = 0;
  // triples that start in `first` (they may straddle into `second`), byte by byte
  for (; k < nFirst && k + 2 < total; k += 3) emit(byteAt(k) << 16 | byteAt(k + 1) << 8 | byteAt(k + 2));
  // whole triples of `second`
  if (k >= nFirst)
    for (const unsigned char* in = second + (k - nFirst); k + 2 < total; k += 3, in += 3)
      emit(static_cast<std::uint32_t>(in[0]) << 16 | static_cast<std::uint32_t>(in[1]) << 8 | in[2]);
  if (k < total) {  // 1 or 2 bytes left: padded
    std::uint32_t v = byteAt(k) << 16;
    if (k + 1 < total) v |= byteAt(k + 1) << 8;
    emit(v);
    o[-1] = '=';
    if (k + 1 >= total) o[-2] = '=';
  }
}

/// One DataArray in VTK "binary" inline encoding: base64(UInt64 byte count + raw little-endian
/// data), encoded straight from the caller's array.
void appendDataArray(std::string& out, const char* type, const std::string& name, int components, const void* data,
                     std::size_t bytes) {
  out += fmt::format("        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"binary\">\n", type,
                     name, components);
  const std::uint64_t count = bytes;
  unsigned char header[sizeof(count)];
  std::memcpy(header, &count, sizeof(count));
  appendBase64(out, header, sizeof(header), static_cast<const unsigned char*>(data), bytes);
  out += "\n        </DataArray>\n";
}

void appendDataArray(std::string& out, const VtkArray& a) {
  if (a.isInteger)
    appendDataArray(out, "Int64", a.name, a.components, a.integer.data(), a.integer.size() * sizeof(std::int64_t));
  else
    appendDataArray(out, "Float64", a.name, a.components, a.real.data(), a.real.size() * sizeof(double));
}

static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 arrays are written as 3-component Float64 arrays");
void appendVectors(std::string& out, const std::string& name, std::span<const Vec3> v) {
  appendDataArray(out, "Float64", name, 3, v.data(), v.size() * sizeof(Vec3));
}
}  // namespace

std::string base64Encode(const void* data, std::size_t size) {
  std::string out;
  appendBase64(out, nullptr, 0, static_cast<const unsigned char*>(data), size);
  return out;
}

std::vector<unsigned char> base64Decode(const std::string& text) {
  int lookup[256];
  std::fill(std::begin(lookup), std::end(lookup), -1);
  for (int i = 0; i < 64; ++i) lookup[static_cast<unsigned char>(kAlphabet[i])] = i;
  std::vector<unsigned char> out;
  std::uint32_t buffer = 0;
  int bits = 0;
  for (unsigned char c : text) {
    if (c == '=') break;
    const int v = lookup[c];
    if (v < 0) continue;  // whitespace
    buffer = (buffer << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((buffer >> bits) & 0xFF));
    }
  }
  return out;
}

std::string particlesVtu(const ParticleArrays& p) {
  const std::size_t n = p.id.size();
  for (const std::size_t size : {p.type.size(), p.radius.size(), p.position.size(), p.velocity.size(),
                                 p.angularVelocity.size(), p.force.size()})
    if (size != n)
      throw Error(fmt::format("particle output: {} ids but an array of {} entries (one entry per particle expected)",
                              n, size));
  std::vector<std::int64_t> connectivity(n), offsets(n);
  const std::vector<std::uint8_t> types(n, 1);  // VTK_VERTEX
  for (std::size_t i = 0; i < n; ++i) {
    connectivity[i] = static_cast<std::int64_t>(i);
    offsets[i] = static_cast<std::int64_t>(i + 1);
  }
  const std::vector<std::int64_t> type(p.type.begin(), p.type.end());
  std::string out;
  // (about 180 characters per particle)
  out.reserve(200 * n + 4096);
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += "  <UnstructuredGrid>\n";
  out += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n, n);
  out += "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n";
  appendDataArray(out, "Int64", "id", 1, p.id.data(), n * sizeof(std::int64_t));
  appendDataArray(out, "Int64", "type", 1, type.data(), n * sizeof(std::int64_t));
  appendDataArray(out, "Float64", "radius", 1, p.radius.data(), n * sizeof(double));
  appendVectors(out, "velocity", p.velocity);
  appendVectors(out, "angular_velocity", p.angularVelocity);
  appendVectors(out, "force", p.force);
  out += "      </PointData>\n";
  out += "      <Points>\n";
  appendVectors(out, "Points", p.position);
  out += "      </Points>\n";
  out += "      <Cells>\n";
  appendDataArray(out, "Int64", "connectivity", 1, connectivity.data(), n * sizeof(std::int64_t));
  appendDataArray(out, "Int64", "offsets", 1, offsets.data(), n * sizeof(std::int64_t));
  appendDataArray(out, "UInt8", "types", 1, types.data(), n);
  out += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return out;
}

VtkArray cellArray(const std::string& name, const Field& field) {
  VtkArray a{name, 1, {}, {}, false};
  const auto& n = field.grid().cells;
  a.real.reserve(field.grid().interiorCellCount());
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) a.real.push_back(field(i, j, k));
  return a;
}

std::string cellFieldsVti(const CartesianGrid& grid, const std::vector<VtkArray>& cellArrays) {
  const auto& n = grid.cells;
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += fmt::format("  <ImageData WholeExtent=\"0 {} 0 {} 0 {}\" Origin=\"{:.17g} {:.17g} {:.17g}\" Spacing=\"{:.17g} {:.17g} {:.17g}\">\n",
                     n[0], n[1], n[2], grid.origin.x, grid.origin.y, grid.origin.z, grid.spacing.x, grid.spacing.y,
                     grid.spacing.z);
  out += fmt::format("    <Piece Extent=\"0 {} 0 {} 0 {}\">\n", n[0], n[1], n[2]);
  out += "      <CellData>\n";
  const std::size_t cells = grid.interiorCellCount();
  for (const VtkArray& a : cellArrays) {
    const std::size_t expected = cells * static_cast<std::size_t>(a.components);
    const std::size_t have = a.isInteger ? a.integer.size() : a.real.size();
    if (have != expected)
      throw Error(fmt::format("internal: cell array '{}' has {} values, grid needs {}", a.name, have, expected));
    appendDataArray(out, a);
  }
  out += "      </CellData>\n    </Piece>\n  </ImageData>\n</VTKFile>\n";
  return out;
}

std::string cellFieldsVtiPiece(const CartesianGrid& grid, const std::array<int, 3>& offset, const CartesianGrid& whole,
                               const std::vector<VtkArray>& cellArrays) {
  // The single-file writer, then the extents moved into the whole grid's index space.
  std::string out = cellFieldsVti(grid, cellArrays);
  const auto& n = grid.cells;
  const std::string local = fmt::format("WholeExtent=\"0 {} 0 {} 0 {}\" Origin=\"{:.17g} {:.17g} {:.17g}\"", n[0], n[1], n[2],
                                        grid.origin.x, grid.origin.y, grid.origin.z);
  const std::string global =
      fmt::format("WholeExtent=\"0 {} 0 {} 0 {}\" Origin=\"{:.17g} {:.17g} {:.17g}\"", whole.cells[0], whole.cells[1],
                  whole.cells[2], whole.origin.x, whole.origin.y, whole.origin.z);
  out.replace(out.find(local), local.size(), global);
  const std::string localPiece = fmt::format("<Piece Extent=\"0 {} 0 {} 0 {}\">", n[0], n[1], n[2]);
  const std::string globalPiece =
      fmt::format("<Piece Extent=\"{} {} {} {} {} {}\">", offset[0], offset[0] + n[0], offset[1], offset[1] + n[1],
                  offset[2], offset[2] + n[2]);
  out.replace(out.find(localPiece), localPiece.size(), globalPiece);
  return out;
}

std::string particlesPvtu(const std::vector<std::string>& pieces) {
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += "  <PUnstructuredGrid GhostLevel=\"0\">\n";
  out += "    <PPointData Scalars=\"radius\" Vectors=\"velocity\">\n";
  out += "      <PDataArray type=\"Int64\" Name=\"id\" NumberOfComponents=\"1\"/>\n";
  out += "      <PDataArray type=\"Int64\" Name=\"type\" NumberOfComponents=\"1\"/>\n";
  out += "      <PDataArray type=\"Float64\" Name=\"radius\" NumberOfComponents=\"1\"/>\n";
  for (const char* v : {"velocity", "angular_velocity", "force"})
    out += fmt::format("      <PDataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"3\"/>\n", v);
  out += "    </PPointData>\n";
  out += "    <PPoints>\n      <PDataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"/>\n    </PPoints>\n";
  for (const std::string& piece : pieces) out += fmt::format("    <Piece Source=\"{}\"/>\n", piece);
  out += "  </PUnstructuredGrid>\n</VTKFile>\n";
  return out;
}

std::string cellFieldsPvti(const CartesianGrid& whole, const std::vector<std::string>& pieces,
                           const std::vector<std::array<int, 6>>& extents, const std::vector<VtkArray>& arrayKinds) {
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"PImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += fmt::format(
      "  <PImageData WholeExtent=\"0 {} 0 {} 0 {}\" GhostLevel=\"0\" Origin=\"{:.17g} {:.17g} {:.17g}\" "
      "Spacing=\"{:.17g} {:.17g} {:.17g}\">\n",
      whole.cells[0], whole.cells[1], whole.cells[2], whole.origin.x, whole.origin.y, whole.origin.z, whole.spacing.x,
      whole.spacing.y, whole.spacing.z);
  out += "    <PCellData>\n";
  for (const VtkArray& a : arrayKinds)
    out += fmt::format("      <PDataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\"/>\n",
                       a.isInteger ? "Int64" : "Float64", a.name, a.components);
  out += "    </PCellData>\n";
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const auto& e = extents[k];
    out += fmt::format("    <Piece Extent=\"{} {} {} {} {} {}\" Source=\"{}\"/>\n", e[0], e[1], e[2], e[3], e[4], e[5],
                       pieces[k]);
  }
  out += "  </PImageData>\n</VTKFile>\n";
  return out;
}

namespace {
std::string attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const std::size_t at = tag.find(key);
  if (at == std::string::npos) return "";
  const std::size_t begin = at + key.size();
  return tag.substr(begin, tag.find('"', begin) - begin);
}
}  // namespace

std::map<std::string, VtkArray> readVtkArrays(const std::string& xml) {
  std::map<std::string, VtkArray> arrays;
  std::size_t pos = 0;
  while ((pos = xml.find("<DataArray", pos)) != std::string::npos) {
    const std::size_t tagEnd = xml.find('>', pos);
    const std::size_t close = xml.find("</DataArray>", tagEnd);
    if (tagEnd == std::string::npos || close == std::string::npos) throw Error("VTK file is truncated");
    const std::string tag = xml.substr(pos, tagEnd - pos);
    pos = close;
    if (attribute(tag, "format") != "binary") continue;
    VtkArray a;
    a.name = attribute(tag, "Name");
    const std::string components = attribute(tag, "NumberOfComponents");
    a.components = components.empty() ? 1 : std::stoi(components);
    const std::vector<unsigned char> raw = base64Decode(xml.substr(tagEnd + 1, close - tagEnd - 1));
    std::uint64_t bytes = 0;
    if (raw.size() >= 8) std::memcpy(&bytes, raw.data(), 8);
    if (raw.size() < 8 || bytes + 8 > raw.size()) throw Error(fmt::format("VTK array '{}' is truncated", a.name));
    const std::string type = attribute(tag, "type");
    if (type == "Float64") {
      a.real.resize(bytes / 8);
      std::memcpy(a.real.data(), raw.data() + 8, bytes);
    } else if (type == "Int64") {
      a.isInteger = true;
      a.integer.resize(bytes / 8);
      std::memcpy(a.integer.data(), raw.data() + 8, bytes);
    } else if (type == "UInt8") {
      a.isInteger = true;
      for (std::uint64_t i = 0; i < bytes; ++i) a.integer.push_back(raw[8 + i]);
    } else {
      continue;
    }
    arrays[a.name] = std::move(a);
  }
  return arrays;
}

void PvdCollection::add(double time, const std::string& relativeFile) {
  entries_.emplace_back(time, relativeFile);
  write();
}

void PvdCollection::truncateAfter(double time) {
  std::erase_if(entries_, [time](const auto& e) { return e.first > time * (1.0 + 1e-12) + 1e-300; });
  write();
}

void PvdCollection::load() {
  entries_.clear();
  if (!std::filesystem::exists(path_)) return;
  const std::string xml = readFile(path_);
  static const std::regex entry(R"re(<DataSet timestep="([^"]+)"[^>]*file="([^"]+)"/>)re");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), entry); it != std::sregex_iterator(); ++it)
    entries_.emplace_back(std::stod((*it)[1]), (*it)[2]);
}

void PvdCollection::write() const {
  std::string out = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n  <Collection>\n";
  for (const auto& [time, file] : entries_)
    out += fmt::format("    <DataSet timestep=\"{:.12g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", time, file);
  out += "  </Collection>\n</VTKFile>\n";
  writeFileAtomically(path_, out);
}

}  // namespace gf::io
