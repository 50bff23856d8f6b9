// Output round trip: write VTK XML, parse it back, compare every array exactly.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>

#include "dem/particles.hpp"
#include "io/atomic_file.hpp"
#include "io/checkpoint.hpp"
#include "io/vtk.hpp"

using namespace gf;

TEST(Base64, RoundTripsAllByteValuesAndLengths) {
  std::vector<unsigned char> bytes(300);
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(i * 7 + 3);
  for (std::size_t n : {0u, 1u, 2u, 3u, 4u, 299u, 300u}) {
    const std::string text = io::base64Encode(bytes.data(), n);
    EXPECT_EQ(text.size() % 4, 0u);
    const auto back = io::base64Decode(text);
    ASSERT_EQ(back.size(), n);
    EXPECT_TRUE(std::equal(back.begin(), back.end(), bytes.begin()));
  }
  EXPECT_EQ(io::base64Encode("Man", 3), "TWFu");  // RFC 4648 example
  EXPECT_EQ(io::base64Encode("Ma", 2), "TWE=");
}

TEST(VtkOutput, ParticlesRoundTrip) {
  dem::ParticleSet p;
  for (int i = 0; i < 37; ++i) {
    const std::size_t k = p.add(1000 + i, i % 3, 0.001 * (1 + i % 5), 2500.0, {0.1 * i, std::sin(i), -1e-7 * i},
                                {1.0 * i, 2.0, 3.0}, {0.5, -0.5, 1e3 * i});
    p.force[k] = {std::cos(i), 1e-20, 3e20};
  }
  const auto arrays = io::readVtkArrays(io::particlesVtu(p));
  ASSERT_EQ(arrays.at("Points").real.size(), 3u * 37u);
  for (int i = 0; i < 37; ++i) {
    EXPECT_EQ(arrays.at("id").integer[i], p.id[i]);
    EXPECT_EQ(arrays.at("type").integer[i], p.type[i]);
    EXPECT_EQ(arrays.at("radius").real[i], p.radius[i]);
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(arrays.at("Points").real[3 * i + c], p.position[i][c]);
      EXPECT_EQ(arrays.at("velocity").real[3 * i + c], p.velocity[i][c]);
      EXPECT_EQ(arrays.at("angular_velocity").real[3 * i + c], p.angularVelocity[i][c]);
      EXPECT_EQ(arrays.at("force").real[3 * i + c], p.force[i][c]);
    }
  }
  EXPECT_EQ(arrays.at("types").integer, std::vector<std::int64_t>(37, 1));  // VTK_VERTEX
}

TEST(VtkOutput, CellFieldsRoundTrip) {
  CartesianGrid grid;
  grid.cells = {3, 4, 5};
  grid.spacing = {0.1, 0.2, 0.3};
  io::VtkArray eps{"void_fraction", 1, {}, {}, false};
  io::VtkArray u{"velocity", 3, {}, {}, false};
  for (std::size_t c = 0; c < grid.interiorCellCount(); ++c) {
    eps.real.push_back(0.4 + 1e-3 * c);
    u.real.insert(u.real.end(), {1.0 * c, -2.0 * c, 1e-9 * c});
  }
  const std::string xml = io::cellFieldsVti(grid, {eps, u});
  EXPECT_NE(xml.find("WholeExtent=\"0 3 0 4 0 5\""), std::string::npos);
  const auto back = io::readVtkArrays(xml);
  EXPECT_EQ(back.at("void_fraction").real, eps.real);
  EXPECT_EQ(back.at("velocity").real, u.real);
  EXPECT_EQ(back.at("velocity").components, 3);
  io::VtkArray wrong{"bad", 1, {1.0}, {}, false};
  EXPECT_THROW(io::cellFieldsVti(grid, {wrong}), Error);
}

TEST(Checkpoint, RoundTripAndRejections) {
  const std::string path = ::testing::TempDir() + "/grainflow_ckpt_test.bin";
  BinaryWriter out;
  out.put<long long>(42);
  out.putVector(std::vector<double>{1.5, -2.5});
  io::writeCheckpoint(path, 0xABCDEF, out);
  const auto payload = io::readCheckpoint(path, 0xABCDEF);
  BinaryReader in(payload.data(), payload.size());
  EXPECT_EQ(in.get<long long>(), 42);
  EXPECT_EQ(in.getVector<double>(), (std::vector<double>{1.5, -2.5}));
  EXPECT_TRUE(in.atEnd());
  EXPECT_THROW(io::readCheckpoint(path, 0x123), CheckpointError);
  std::string bytes = io::readFile(path);
  bytes[bytes.size() - 12] ^= 1;
  io::writeFileAtomically(path, bytes);
  EXPECT_THROW(io::readCheckpoint(path, 0xABCDEF), CheckpointError);
}

TEST(PvdCollection, TruncatesAfterRestartTime) {
  const std::string path = ::testing::TempDir() + "/grainflow_series_test.pvd";
  io::PvdCollection series(path);
  for (int i = 0; i < 5; ++i) series.add(0.1 * i, fmt::format("f{}.vtu", i));
  io::PvdCollection reread(path);
  reread.load();
  EXPECT_EQ(reread.size(), 5u);
  reread.truncateAfter(0.2);
  io::PvdCollection again(path);
  again.load();
  EXPECT_EQ(again.size(), 3u);
}
