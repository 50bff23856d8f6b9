// Closed STL meshes as fixed resolved bodies (src/resolved/mesh_body.hpp): the solid fractions of an
// icosphere add up to its volume within the sampling error and to the sphere's within the
// tessellation's, a cube aligned with the cell faces gives its volume exactly, either triangle
// orientation gives the same fractions; and the drag of a fixed sphere given as an STL mesh matches
// the analytic sphere's on the same grid.
#include "resolved/mesh_body.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>

#include "../app/run_helper.hpp"
#include "app/simulation.hpp"
#include "core/parallel.hpp"
#include "core/params.hpp"
#include "resolved/forcing.hpp"
#include "resolved/overlap.hpp"

namespace gf::resolved {
namespace {

constexpr double kPi = std::numbers::pi;

/// Icosahedron subdivided `levels` times, its vertices on the sphere (centre c, radius r); outward
/// orientation (20 x 4^levels triangles).
std::vector<io::Triangle> icosphere(const Vec3& c, double r, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& p : v) p = p / norm(p);
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      const Vec3 m = (v[a] + v[b]) / 2.0;
      v.push_back(m / norm(m));
      middle[key] = static_cast<int>(v.size()) - 1;
      return static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& q : f) {
      const int a = mid(q[0], q[1]), b = mid(q[1], q[2]), d = mid(q[2], q[0]);
      next.push_back({q[0], a, d});
      next.push_back({q[1], b, a});
      next.push_back({q[2], d, b});
      next.push_back({a, b, d});
    }
    f = next;
  }
  std::vector<io::Triangle> out;
  for (const auto& q : f) out.push_back({c + r * v[q[0]], c + r * v[q[1]], c + r * v[q[2]]});
  return out;
}

/// The box [lo, hi] as 12 outward triangles.
std::vector<io::Triangle> boxMesh(const Vec3& lo, const Vec3& hi) {
  auto p = [&](int i, int j, int k) { return Vec3{i ? hi.x : lo.x, j ? hi.y : lo.y, k ? hi.z : lo.z}; };
  return {{p(0, 0, 0), p(0, 1, 0), p(1, 1, 0)}, {p(0, 0, 0), p(1, 1, 0), p(1, 0, 0)},   // z = lo
          {p(0, 0, 1), p(1, 0, 1), p(1, 1, 1)}, {p(0, 0, 1), p(1, 1, 1), p(0, 1, 1)},   // z = hi
          {p(0, 0, 0), p(1, 0, 0), p(1, 0, 1)}, {p(0, 0, 0), p(1, 0, 1), p(0, 0, 1)},   // y = lo
          {p(0, 1, 0), p(0, 1, 1), p(1, 1, 1)}, {p(0, 1, 0), p(1, 1, 1), p(1, 1, 0)},   // y = hi
          {p(0, 0, 0), p(0, 0, 1), p(0, 1, 1)}, {p(0, 0, 0), p(0, 1, 1), p(0, 1, 0)},   // x = lo
          {p(1, 0, 0), p(1, 1, 0), p(1, 1, 1)}, {p(1, 0, 0), p(1, 1, 1), p(1, 0, 1)}};  // x = hi
}

CartesianGrid cube(int n, double h) {
  CartesianGrid g;
  g.origin = Vec3{0, 0, 0};
  g.spacing = Vec3{h, h, h};
  g.cells = {n, n, n};
  return g;
}

/// Sum of the cells' fractions times the cell volume.
double cellVolumeSum(const MeshBody& m, const CartesianGrid& g) {
  double sum = 0.0;
  for (int k = 0; k < g.cells[2]; ++k)
    for (int j = 0; j < g.cells[1]; ++j)
      for (int i = 0; i < g.cells[0]; ++i) {
        const Vec3 lo{i * g.spacing.x, j * g.spacing.y, k * g.spacing.z};
        sum += m.fraction(lo, lo + g.spacing) * g.cellVolume();
      }
  return sum;
}

TEST(ResolvedMeshBody, IcosphereFractionsAddUpToItsVolume) {
  // d = 8 cells (h = 1), 5120 triangles, 8 samples per cell along each axis, at an arbitrary centre.
  const Vec3 c{8.137, 7.861, 8.409};
  const double r = 4.0;
  const auto mesh = icosphere(c, r, 4);
  const double polyhedron = meshVolume(mesh), sphere = 4.0 / 3.0 * kPi * r * r * r;
  // The polyhedron is inside the sphere: its volume short by the tessellation error (0.22 % here).
  EXPECT_LT(polyhedron, sphere);
  EXPECT_GT(polyhedron, 0.99 * sphere);
  const Vec3 centroid = meshCentroid(mesh);
  EXPECT_LT(norm(centroid - c), 1e-9 * r);
  const CartesianGrid g = cube(17, 1.0);
  const MeshBody body(mesh, g, 8);
  EXPECT_NEAR(body.volume(), polyhedron, 1e-12 * polyhedron);
  const double sampled = cellVolumeSum(body, g);
  std::printf("icosphere: polyhedron / sphere %.5f, sampled / polyhedron %.6f\n", polyhedron / sphere, sampled / polyhedron);
  EXPECT_NEAR(sampled, polyhedron, 1e-3 * polyhedron);  // sampling error (midpoint rule of an indicator): 3.2e-4
  EXPECT_NEAR(sampled, sphere, 3e-3 * sphere);          // and the tessellation's: 1.8e-3
  // Cell by cell against the exact sphere-box volumes: within the cut cells' sampling error.
  double worst = 0.0;
  for (int k = 0; k < 17; ++k)
    for (int j = 0; j < 17; ++j)
      for (int i = 0; i < 17; ++i) {
        const Vec3 lo{double(i), double(j), double(k)};
        worst = std::max(worst, std::abs(body.fraction(lo, lo + Vec3{1, 1, 1}) -
                                         sphereBoxFraction(c, r, lo, lo + Vec3{1, 1, 1})));
      }
  std::printf("icosphere: largest difference of a cell's fraction from the sphere's %.4f\n", worst);
  EXPECT_LT(worst, 0.04);  // (0.022)
  // A face's control volume (half a cell off along x) is counted from the same samples: the same as
  // sampling that box directly (off the half-cell lattice the box is sampled on its own).
  for (const Vec3& lo : {Vec3{4.5, 7.0, 8.0}, Vec3{10.0, 5.5, 6.0}, Vec3{6.0, 9.0, 4.5}}) {
    const double lattice = body.fraction(lo, lo + Vec3{1, 1, 1});
    const Vec3 off = lo + Vec3{1e-3, 0, 0};  // off the lattice: direct sampling of a nearly equal box
    EXPECT_NEAR(body.fraction(off, off + Vec3{1, 1, 1}), lattice, 0.03) << lo.x << " " << lo.y << " " << lo.z;
  }
  // Inside, outside, distance to the surface.
  EXPECT_TRUE(body.contains(c));
  EXPECT_TRUE(body.contains(c + Vec3{0.99 * r * std::cos(0.3), 0.0, 0.99 * r * std::sin(0.3)} * 0.98));
  EXPECT_FALSE(body.contains(c + Vec3{1.01 * r, 0.0, 0.0}));
  EXPECT_FALSE(body.contains(c + Vec3{0.0, 3.0 * r, 0.0}));
  EXPECT_NEAR(body.distance(c + Vec3{0.0, 0.0, 2.0 * r}), r, 0.01 * r);
  EXPECT_NEAR(body.distance(c), r, 0.01 * r);
}

TEST(ResolvedMeshBody, CubeAlignedWithTheCellFacesIsExact) {
  // A cube of 4 x 3 x 5 cells with its faces on cell faces: every cell 0 or 1, the sum its volume
  // exactly, the control volumes of the faces on its surface half covered.
  const double h = 0.25;
  const CartesianGrid g = cube(12, h);
  const Vec3 lo{2 * h, 3 * h, 4 * h}, hi{6 * h, 6 * h, 9 * h};
  for (bool flip : {false, true}) {
    auto mesh = boxMesh(lo, hi);
    if (flip)  // inward orientation: parity does not care
      for (io::Triangle& t : mesh) std::swap(t[1], t[2]);
    const MeshBody body(mesh, g, 8);
    EXPECT_DOUBLE_EQ(body.volume(), 4 * 3 * 5 * h * h * h);
    EXPECT_NEAR(cellVolumeSum(body, g), 60 * h * h * h, 1e-15);
    for (int k = 0; k < 12; ++k)
      for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 12; ++i) {
          const Vec3 c{i * h, j * h, k * h};
          const double phi = body.fraction(c, c + g.spacing);
          const bool in = i >= 2 && i < 6 && j >= 3 && j < 6 && k >= 4 && k < 9;
          ASSERT_EQ(phi, in ? 1.0 : 0.0) << i << " " << j << " " << k;
        }
    // The u face at x = 2 h (the cube's lower x face), cell (., 4, 6): its control volume
    // [1.5 h, 2.5 h] x [4 h, 5 h] x [6 h, 7 h] is half inside.
    const Vec3 face{1.5 * h, 4 * h, 6 * h};
    EXPECT_EQ(body.fraction(face, face + g.spacing), 0.5);
  }
}

TEST(ResolvedMeshBody, ForcingVisitsTheSameCellsAsTheAnalyticSphere) {
  // The covered cells of an icosphere body and of the analytic sphere: the same total fraction (the
  // bounding box of the mesh bounds the loops).
  const Vec3 c{2.03, 1.97, 2.11};
  const double r = 0.5, h = 0.125;
  FaceBox box;
  box.grid = cube(32, h);
  box.global = {32, 32, 32};
  Body mesh;
  mesh.shape = Shape::Mesh;
  mesh.mesh = std::make_shared<const MeshBody>(icosphere(c, r, 4), box.grid, 8);
  mesh.centre = c;
  mesh.radius = r;
  Body sphere;
  sphere.centre = c;
  sphere.radius = r;
  double a = 0.0, b = 0.0;
  forEachCoveredCell(mesh, box, [&](int, int, int, const Vec3&, double phi) { a += phi; });
  forEachCoveredCell(sphere, box, [&](int, int, int, const Vec3&, double phi) { b += phi; });
  EXPECT_NEAR(a * box.grid.cellVolume(), mesh.mesh->volume(), 2e-3 * mesh.mesh->volume());
  EXPECT_NEAR(a, b, 6e-3 * b);
  EXPECT_NEAR(bodyVolume(mesh, 1.0), mesh.mesh->volume(), 0.0);
}

using gf::testing::grainflow;
using gf::testing::readAll;
using gf::testing::TempDir;

void writeAsciiStl(const std::string& path, const std::vector<io::Triangle>& mesh) {
  std::ofstream out(path);
  out.precision(17);
  out << "solid body\n";
  for (const io::Triangle& t : mesh) {
    const Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
    out << " facet normal " << n.x << " " << n.y << " " << n.z << "\n  outer loop\n";
    for (const Vec3& v : t) out << "   vertex " << v.x << " " << v.y << " " << v.z << "\n";
    out << "  endloop\n endfacet\n";
  }
  out << "endsolid body\n";
}

/// Mean of column `column` over the rows of a monitor CSV with time > t0.
double meanAfter(const std::string& csv, std::size_t column, double t0) {
  std::istringstream in(readAll(csv));
  std::string line;
  double sum = 0.0;
  int count = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    std::vector<double> v;
    std::istringstream row(line);
    std::string cell;
    while (std::getline(row, cell, ',')) v.push_back(std::stod(cell));
    if (v.size() > column && v[0] > t0) {
      sum += v[column];
      ++count;
    }
  }
  return count > 0 ? sum / count : std::nan("");
}

TEST(ResolvedMeshBody, FixedSphereFromAnStlFileHasTheAnalyticSpheresDrag) {
  // A fixed sphere of D = 0.1 m at 8 cells per diameter in a stream of 1 m/s (Re 100), 30 fluid steps
  // of 5 ms: the drag of the icosphere (5120 triangles, written as ASCII STL) against that of the
  // analytic sphere body on the same grid, the mean over the last 20 steps.
  TempDir dir;
  const double r = 0.05;
  writeAsciiStl(dir.file("sphere.stl"), icosphere(Vec3{0, 0, 0}, r, 4));
  auto caseText = [&](const std::string& body) {
    return R"(
case: {name: resolved_stl_sphere}
domain: {min: [0, 0, 0], max: [0.6, 0.4, 0.4]}
gravity: [0, 0, 0]
materials: [{name: unused, density: 2500.0}]
time: {end: 0.15, dem_step: 0.005, coupling_interval: 1}
output: {interval: 1.0}
fluid:
  density: 1.0
  viscosity: 0.001
  cells: [48, 32, 32]
  convection: central
  boundaries:
    x_min: {type: inlet, velocity: [1.0, 0.0, 0.0]}
    x_max: {type: pressure_outlet, pressure: 0.0}
    y_min: {type: slip}
    y_max: {type: slip}
    z_min: {type: slip}
    z_max: {type: slip}
resolved:
  bodies:
    - )" + body + R"(
monitors:
  - {type: resolved_body_forces, name: forces, body: 0, reference_velocity: 1.0, interval: 0}
)";
  };
  const std::string analytic = dir.write("analytic.yaml", caseText("{shape: sphere, centre: [0.2, 0.2, 0.2], radius: 0.05}"));
  const std::string stl =
      dir.write("stl.yaml", caseText("{shape: stl, file: sphere.stl, offset: [0.2, 0.2, 0.2], centre: [0.2, 0.2, 0.2]}"));
  const auto a = grainflow("run " + analytic + " --quiet --threads 1 --output " + dir.file("a"));
  ASSERT_EQ(a.exitCode, 0) << a.output;
  const auto s = grainflow("run " + stl + " --quiet --threads 1 --output " + dir.file("s"));
  ASSERT_EQ(s.exitCode, 0) << s.output;
  const double fa = meanAfter(dir.file("a/forces.csv"), 1, 0.05), fs = meanAfter(dir.file("s/forces.csv"), 1, 0.05);
  const double lift = meanAfter(dir.file("s/forces.csv"), 2, 0.05);
  std::printf("fixed sphere, drag of the analytic body %.6g N, of the STL body %.6g N (ratio %.4f); STL lift %.3g N\n", fa,
              fs, fs / fa, lift);
  EXPECT_GT(fa, 0.0);
  EXPECT_NEAR(fs / fa, 1.0, 0.03);
  EXPECT_LT(std::abs(lift), 0.05 * fa);
}

TEST(ResolvedMeshBody, StlBodyOnFourRanksMatchesOneRank) {
  // The cube case cut into 2 x 2 boxes through the cube (moved onto both cuts): each rank counts the
  // samples of its own box and the cells around it, forces its own cells and sums its loads; the
  // forces agree with one rank's far inside the tolerance (only the order of the sums differs).
  if (gf::testing::runShell("command -v mpirun").exitCode != 0) GTEST_SKIP() << "no mpirun";
  TempDir dir;
  const std::string source = std::string(GRAINFLOW_SOURCE_DIR) + "/cases/";
  std::string text = readAll(source + "resolved_stl_cube.yaml");
  const std::string body = "file: meshes/cube.stl, offset: [0.3, 0.3, 0.3]";
  ASSERT_NE(text.find(body), std::string::npos);
  text.replace(text.find(body), body.size(), "file: " + source + "meshes/cube.stl, offset: [0.6, 0.3, 0.3]");
  const std::string every = "interval: 0.05}";  // (the monitor: every step)
  ASSERT_NE(text.find(every), std::string::npos);
  text.replace(text.find(every), every.size(), "interval: 0}");
  const std::string one = dir.write("one.yaml", text);
  const std::string max = "  max: [1.2, 0.6, 0.6]";
  ASSERT_NE(text.find(max), std::string::npos);
  text.replace(text.find(max), max.size(), max + "\n  decomposition: [2, 2, 1]");
  const std::string four = dir.write("four.yaml", text);
  const auto r1 = grainflow("run " + one + " --quiet --threads 1 --end-time 0.02 --output " + dir.file("o1"));
  ASSERT_EQ(r1.exitCode, 0) << r1.output;
  const auto r4 = gf::testing::grainflowOnRanks(4, "run " + four + " --quiet --threads 1 --end-time 0.02 --output " + dir.file("o4"));
  ASSERT_EQ(r4.exitCode, 0) << r4.output;
  const double f1 = meanAfter(dir.file("o1/cube_forces.csv"), 1, 0.0), f4 = meanAfter(dir.file("o4/cube_forces.csv"), 1, 0.0);
  std::printf("cube on one rank %.9g N, on four %.9g N\n", f1, f4);
  EXPECT_GT(f1, 0.0);
  EXPECT_NEAR(f4, f1, 1e-7 * f1);
}

/// A sphere of d = 2 mm, 1500 kg/m^3, settling from 0.15 d above a fixed block (an stl body of 3 x 3 x
/// 0.9 mm, its faces on cell faces) in a closed box of 3 d of liquid, 6.7 cells per d; with `wall`, a DEM
/// stl wall of the same file (the particle's contacts with the body: docs/resolved.md sec. 7). The
/// sphere's lowest point above the block's top, over d, after each of `steps` fluid steps of 0.25 ms.
std::vector<double> sphereOntoBlock(const TempDir& dir, bool wall, int steps) {
  const std::string stl = dir.file("block.stl");
  writeAsciiStl(stl, boxMesh(Vec3{0.0015, 0.0015, 0.0006}, Vec3{0.0045, 0.0045, 0.0015}));
  const std::string text = R"(
case: {name: resolved_sphere_onto_block}
domain: {min: [0, 0, 0], max: [0.006, 0.006, 0.006]}
gravity: [0, 0, -9.81]
time: {end: 1.0, dem_step: 2.5e-5, coupling_interval: 10}
materials:
  - {name: sphere, density: 1500.0, youngs_modulus: 1.0e5, poisson_ratio: 0.3, restitution: 0.5, friction: 0.1}
)" + (wall ? "walls:\n  - {type: stl, file: " + stl + "}\n" : std::string()) +
                           R"(insertion:
  - {type: lattice, material: sphere, origin: [0.003, 0.003, 0.0028], nx: 1, ny: 1, nz: 1, spacing: 0.004,
     diameter: 0.002}
fluid: {density: 1000.0, viscosity: 0.01, cells: [20, 20, 20]}
output: {interval: 0}
resolved:
  bodies:
    - {shape: stl, file: )" + stl + R"(}
)";
  const int threads = threadCount();  // (one thread, as the command line's --threads 1)
  setThreadCount(1);
  Params root = Params::loadString(text, dir.file("block.yaml"));
  app::RunOptions options;
  options.threads = 1;
  options.quiet = true;
  app::Simulation sim(root, dir.file("block.yaml"), options);
  std::vector<double> gaps;
  for (int n = 0; n < steps; ++n) {
    sim.advance();
    const dem::ParticleSet& p = sim.dem().particles();
    gaps.push_back((p.position[0].z - p.radius[0] - 0.0015) / (2.0 * p.radius[0]));
  }
  setThreadCount(threads);
  return gaps;
}

TEST(ResolvedMeshBody, ParticleRestsOnAnStlBodyThroughADemWallOfTheSameMesh) {
  // Without the DEM wall the sphere sinks into the block (the forcing alone does not stop it); with it
  // the sphere lands on the block and stays on its top within the DEM contact's overlap.
  TempDir dir;
  constexpr int kSteps = 160;  // 40 ms
  const std::vector<double> without = sphereOntoBlock(dir, false, kSteps), with = sphereOntoBlock(dir, true, kSteps);
  for (int n = 19; n < kSteps; n += 20)
    std::printf("t %.4f s  gap/d without the wall %.4f  with %.4f\n", (n + 1) * 2.5e-4, without[n], with[n]);
  EXPECT_LT(without.back(), -0.01);
  EXPECT_LT(*std::min_element(with.begin(), with.end()), 0.0);  // it landed
  EXPECT_GT(*std::min_element(with.begin(), with.end()), -0.02);
  EXPECT_GT(with.back(), -0.02);
}

TEST(ResolvedMeshBody, ParticleOverlappingAnStlBodyIsRefusedWithItsId) {
  TempDir dir;
  writeAsciiStl(dir.file("block.stl"), boxMesh(Vec3{0.006, 0.006, 0.020}, Vec3{0.010, 0.010, 0.0235}));
  std::string text = readAll(std::string(GRAINFLOW_SOURCE_DIR) + "/cases/resolved_settling_sphere.yaml");
  const std::string from = "resolved: {}";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), "resolved:\n  bodies:\n    - {shape: stl, file: block.stl}");
  const auto r = grainflow("check " + dir.write("overlap.yaml", text));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("resolved.bodies[0].file"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("particle(s) 0 overlapping body 0"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace gf::resolved
