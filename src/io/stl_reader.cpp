#include "io/stl_reader.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/error.hpp"

namespace gf::io {

namespace {

std::vector<Triangle> parseBinary(const std::string& bytes) {
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  std::vector<Triangle> out(count);
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* rec = bytes.data() + 84 + 50 * static_cast<std::size_t>(t) + 12;  // skip the normal
    for (int v = 0; v < 3; ++v) {
      float xyz[3];
      std::memcpy(xyz, rec + 12 * v, 12);
      out[t][v] = {xyz[0], xyz[1], xyz[2]};
    }
  }
  return out;
}

std::vector<Triangle> parseAscii(const std::string& text, const std::string& path) {
  std::istringstream in(text);
  std::vector<Triangle> out;
  std::string word;
  Triangle tri;
  int vertex = 0;
  while (in >> word) {
    if (word == "vertex") {
      Vec3 v;
      if (!(in >> v.x >> v.y >> v.z)) throw Error(fmt::format("{}: malformed 'vertex' line in ASCII STL", path));
      if (vertex < 3) tri[vertex] = v;
      ++vertex;
    } else if (word == "endfacet") {
      if (vertex != 3) throw Error(fmt::format("{}: facet with {} vertices (expected 3)", path, vertex));
      out.push_back(tri);
      vertex = 0;
    }
  }
  if (out.empty()) throw Error(fmt::format("{}: no facets found (neither valid binary nor ASCII STL)", path));
  return out;
}

}  // namespace

std::vector<Triangle> readStl(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(fmt::format("cannot open STL file '{}'", path));
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (bytes.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() == 84 + 50 * static_cast<std::size_t>(count)) return parseBinary(bytes);
  }
  return parseAscii(bytes, path);
}

}  // namespace gf::io
