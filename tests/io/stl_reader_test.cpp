// STL input: ASCII and binary files give the same triangles; bad files give an error naming them.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "io/stl_reader.hpp"

using namespace gf;

namespace {

const std::filesystem::path kTmp = std::filesystem::temp_directory_path() / "grainflow_io_stl_reader_test";

// Square [-L, L]^2 at z = 0 as two triangles.
void writeStl(const std::filesystem::path& path, bool binary, double L) {
  const float v[2][3][3] = {{{-float(L), -float(L), 0}, {float(L), -float(L), 0}, {float(L), float(L), 0}},
                            {{-float(L), -float(L), 0}, {float(L), float(L), 0}, {-float(L), float(L), 0}}};
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  if (binary) {
    char header[80] = {};
    out.write(header, 80);
    const std::uint32_t n = 2;
    out.write(reinterpret_cast<const char*>(&n), 4);
    for (const auto& t : v) {
      const float normal[3] = {0, 0, 1};
      out.write(reinterpret_cast<const char*>(normal), 12);
      out.write(reinterpret_cast<const char*>(t), 36);
      const std::uint16_t attr = 0;
      out.write(reinterpret_cast<const char*>(&attr), 2);
    }
  } else {
    out << "solid square\n";
    for (const auto& t : v) {
      out << " facet normal 0 0 1\n  outer loop\n";
      for (const auto& p : t) out << "   vertex " << p[0] << " " << p[1] << " " << p[2] << "\n";
      out << "  endloop\n endfacet\n";
    }
    out << "endsolid square\n";
  }
}

std::string errorOf(const std::filesystem::path& path) {
  try {
    io::readStl(path.string());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(StlReader, AsciiAndBinaryReadTheSameTriangles) {
  writeStl(kTmp / "a.stl", false, 0.01);
  writeStl(kTmp / "b.stl", true, 0.01);
  const auto a = io::readStl((kTmp / "a.stl").string()), b = io::readStl((kTmp / "b.stl").string());
  ASSERT_EQ(a.size(), 2u);
  ASSERT_EQ(b.size(), 2u);
  for (int t = 0; t < 2; ++t)
    for (int v = 0; v < 3; ++v) EXPECT_LT(norm(a[t][v] - b[t][v]), 1e-9);  // binary holds floats
  EXPECT_EQ(b[0][1], (Vec3{0.01f, -0.01f, 0.0}));
}

TEST(StlReader, BadFilesNameTheFileAndTheFault) {
  EXPECT_NE(errorOf(kTmp / "missing.stl").find("cannot open STL file"), std::string::npos);
  std::filesystem::create_directories(kTmp);
  std::ofstream(kTmp / "two_vertices.stl") << "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                              "endloop\nendfacet\nendsolid s\n";
  const std::string twoVertices = errorOf(kTmp / "two_vertices.stl");
  EXPECT_NE(twoVertices.find("two_vertices.stl"), std::string::npos) << twoVertices;
  EXPECT_NE(twoVertices.find("facet with 2 vertices"), std::string::npos) << twoVertices;
  std::ofstream(kTmp / "empty.stl") << "not an STL file\n";
  EXPECT_NE(errorOf(kTmp / "empty.stl").find("no facets found"), std::string::npos);
}
