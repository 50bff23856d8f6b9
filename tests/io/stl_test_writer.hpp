#pragma once
// Test helper: writes triangles as an ASCII or binary STL file, for the tests that read meshes
// (tests/io/stl_reader_test.cpp, tests/dem/walls_test.cpp, tests/fluid/blocked_stl_test.cpp).
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/vec3.hpp"

namespace gf::testing {

using StlTriangle = std::array<Vec3, 3>;

/// The square [-L, L]^2 at z = 0 as two triangles, normal +z.
inline std::vector<StlTriangle> squareTriangles(double L) {
  return {{Vec3{-L, -L, 0}, Vec3{L, -L, 0}, Vec3{L, L, 0}}, {Vec3{-L, -L, 0}, Vec3{L, L, 0}, Vec3{-L, L, 0}}};
}

/// Writes `triangles` to `path` (directories created), binary (float vertices, zero normals and
/// attributes) or ASCII. Normals are left zero: the reader computes them from the vertices.
inline void writeStl(const std::filesystem::path& path, const std::vector<StlTriangle>& triangles, bool binary) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  if (binary) {
    char header[80] = {};
    out.write(header, 80);
    const auto n = static_cast<std::uint32_t>(triangles.size());
    out.write(reinterpret_cast<const char*>(&n), 4);
    for (const auto& t : triangles) {
      const float normal[3] = {0, 0, 0};
      out.write(reinterpret_cast<const char*>(normal), 12);
      for (const Vec3& v : t) {
        const float f[3] = {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
        out.write(reinterpret_cast<const char*>(f), 12);
      }
      const std::uint16_t attr = 0;
      out.write(reinterpret_cast<const char*>(&attr), 2);
    }
  } else {
    out << "solid mesh\n";
    for (const auto& t : triangles) {
      out << " facet normal 0 0 0\n  outer loop\n";
      for (const Vec3& v : t) out << "   vertex " << v.x << " " << v.y << " " << v.z << "\n";
      out << "  endloop\n endfacet\n";
    }
    out << "endsolid mesh\n";
  }
}

}  // namespace gf::testing
