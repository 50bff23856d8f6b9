// Every cases/fluid_*.yaml builds a solver and runs a few stable steps (shortened runs).
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "core/domain.hpp"
#include "core/monitor.hpp"
#include "fluid/solver.hpp"

namespace gf::fluid {
namespace {

TEST(Cases, FluidCasesRunShortened) {
  std::set<std::string> expected = {"fluid_cavity.yaml", "fluid_channel.yaml", "fluid_cylinder.yaml"};
  int found = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(GRAINFLOW_SOURCE_DIR) + "/cases")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("fluid_", 0) != 0 || entry.path().extension() != ".yaml") continue;
    ++found;
    expected.erase(name);
    SCOPED_TRACE(name);
    Params root = Params::loadFile(entry.path().string());
    const Domain domain = Domain::read(root);
    Solver s(root, domain, root.vec3({"gravity", "m/s^2", "gravity"}, Vec3{}));
    RunState state;
    state.fluid = &s;
    std::vector<std::unique_ptr<Monitor>> monitors;
    for (Params& m : root.list({"monitors", "-", "monitors"}))
      monitors.push_back(Registry<Monitor>::instance().create(m, {"type", "-", "monitor"}));
    for (int n = 0; n < 5; ++n) {
      s.step(std::min(s.stableTimeStep(), 1e-3));
      s.checkHealth(n, s.time());
      for (auto& m : monitors)
        for (double v : m->sample(state)) EXPECT_TRUE(std::isfinite(v));
    }
    EXPECT_LT(s.lastStep().pressureResidual, 1e-8);
  }
  EXPECT_GE(found, 3);
  EXPECT_TRUE(expected.empty()) << "example case not found: " << *expected.begin();
}

}  // namespace
}  // namespace gf::fluid

namespace gf::fluid {
namespace {

TEST(Cases, DocumentationModeListsFluidKeys) {
  Params doc = Params::documentation();
  Domain d;
  d.min = Vec3{0, 0, 0};
  d.max = Vec3{1, 1, 1};
  Solver s(doc, d, Vec3{});
  bool density = false, boundaries = false, blocked = false;
  for (const auto& k : doc.documentedKeys()) {
    density = density || k.path == "fluid.density";
    boundaries = boundaries || k.path.find("fluid.boundaries.x_min.type") != std::string::npos;
    blocked = blocked || k.path.find("blocked") != std::string::npos;
  }
  EXPECT_TRUE(density);
  EXPECT_TRUE(boundaries);
  EXPECT_TRUE(blocked);
}

}  // namespace
}  // namespace gf::fluid
