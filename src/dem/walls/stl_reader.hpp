#pragma once
// Reads triangles from ASCII or binary STL files.
#include <array>
#include <string>
#include <vector>

#include "core/vec3.hpp"

namespace gf::dem {

using Triangle = std::array<Vec3, 3>;

/// Binary if the size matches 84 + 50 n for the count n in the header, else ASCII.
/// Throws gf::Error naming the file on unreadable or malformed input.
std::vector<Triangle> readStl(const std::string& path);

}  // namespace gf::dem
