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

/// VTK "binary" inline encoding: base64(UInt64 byte count + raw little-endian data).
template <class T>
std::string encodeArray(const std::vector<T>& values) {
  const std::uint64_t bytes = values.size() * sizeof(T);
  std::vector<unsigned char> raw(sizeof(bytes) + bytes);
  std::memcpy(raw.data(), &bytes, sizeof(bytes));
  if (bytes) std::memcpy(raw.data() + sizeof(bytes), values.data(), bytes);
  return base64Encode(raw.data(), raw.size());
}

void appendDataArray(std::string& out, const VtkArray& a) {
  if (a.isInteger)
    out += fmt::format("        <DataArray type=\"Int64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"binary\">\n{}\n        </DataArray>\n",
                       a.name, a.components, encodeArray(a.integer));
  else
    out += fmt::format("        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"binary\">\n{}\n        </DataArray>\n",
                       a.name, a.components, encodeArray(a.real));
}

VtkArray vectorArray(const std::string& name, const std::vector<Vec3>& v) {
  VtkArray a{name, 3, {}, {}, false};
  a.real.reserve(3 * v.size());
  for (const Vec3& x : v) a.real.insert(a.real.end(), {x.x, x.y, x.z});
  return a;
}
}  // namespace

std::string base64Encode(const void* data, std::size_t size) {
  const auto* in = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < size; i += 3) {
    const std::uint32_t v = (in[i] << 16) | (in[i + 1] << 8) | in[i + 2];
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i < size) {
    std::uint32_t v = in[i] << 16;
    if (i + 1 < size) v |= in[i + 1] << 8;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += (i + 1 < size) ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
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

std::string particlesVtu(const dem::ParticleSet& p) {
  const std::size_t n = p.size();
  std::vector<double> points;
  points.reserve(3 * n);
  for (const Vec3& x : p.position) points.insert(points.end(), {x.x, x.y, x.z});
  std::vector<std::int64_t> connectivity(n), offsets(n);
  std::vector<std::uint8_t> types(n, 1);  // VTK_VERTEX
  for (std::size_t i = 0; i < n; ++i) {
    connectivity[i] = static_cast<std::int64_t>(i);
    offsets[i] = static_cast<std::int64_t>(i + 1);
  }
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += "  <UnstructuredGrid>\n";
  out += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n, n);
  out += "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n";
  std::vector<std::int64_t> type(p.type.begin(), p.type.end());
  appendDataArray(out, {"id", 1, {}, p.id, true});
  appendDataArray(out, {"type", 1, {}, type, true});
  appendDataArray(out, {"radius", 1, p.radius, {}, false});
  appendDataArray(out, vectorArray("velocity", p.velocity));
  appendDataArray(out, vectorArray("angular_velocity", p.angularVelocity));
  appendDataArray(out, vectorArray("force", p.force));
  out += "      </PointData>\n";
  out += "      <Points>\n";
  appendDataArray(out, {"Points", 3, points, {}, false});
  out += "      </Points>\n";
  out += "      <Cells>\n";
  appendDataArray(out, {"connectivity", 1, {}, connectivity, true});
  appendDataArray(out, {"offsets", 1, {}, offsets, true});
  out += fmt::format("        <DataArray type=\"UInt8\" Name=\"types\" format=\"binary\">\n{}\n        </DataArray>\n",
                     encodeArray(types));
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
