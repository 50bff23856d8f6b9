#pragma once
// Reads triangles from ASCII or binary STL files: the DEM's mesh walls and the fluid's blocked
// regions read the same meshes, so the reader lives in io, which both may use.
#include <array>
#include <string>
#include <vector>

#include "core/vec3.hpp"

namespace gf::io {

using Triangle = std::array<Vec3, 3>;

/// Binary if the size matches 84 + 50 n for the count n in the header, else ASCII.
/// Throws gf::Error naming the file on unreadable or malformed input.
std::vector<Triangle> readStl(const std::string& path);

}  // namespace gf::io
