// STL input: ASCII and binary files give the same triangles; bad files give an error naming them.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "io/stl_reader.hpp"
#include "stl_test_writer.hpp"

using namespace gf;

namespace {

const std::filesystem::path kTmp = std::filesystem::temp_directory_path() / "grainflow_io_stl_reader_test";

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
  gf::testing::writeStl(kTmp / "a.stl", gf::testing::squareTriangles(0.01), false);
  gf::testing::writeStl(kTmp / "b.stl", gf::testing::squareTriangles(0.01), true);
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
