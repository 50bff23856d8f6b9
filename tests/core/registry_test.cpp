#include <gtest/gtest.h>

#include "core/parallel.hpp"
#include "core/registry.hpp"

namespace {
struct Shape {
  virtual ~Shape() = default;
  virtual double area() const = 0;
};
struct Square : Shape {
  explicit Square(gf::Params& p) : side(p.real({"side", "m", "edge length", gf::Range::positive()})) {}
  double area() const override { return side * side; }
  double side;
};
struct Disc : Shape {
  explicit Disc(gf::Params& p) : radius(p.real({"radius", "m", "", gf::Range::positive()}, 1.0)) {}
  double area() const override { return 3.0 * radius * radius; }
  double radius;
};
}  // namespace

GF_REGISTER_MODEL(Shape, Square, "square", "a square")
GF_REGISTER_MODEL(Shape, Disc, "disc", "a disc")

TEST(Registry, CreatesByNameAndListsNamesOnTypo) {
  gf::Params p = gf::Params::loadString("shape: {model: square, side: 2}\nother: {model: squre}\n", "r.yaml");
  gf::Params s = p.section({"shape"});
  std::string chosen;
  auto shape = gf::Registry<Shape>::instance().create(s, {"model"}, "", &chosen);
  EXPECT_EQ(chosen, "square");
  EXPECT_DOUBLE_EQ(shape->area(), 4.0);
  gf::Params o = p.section({"other"});
  try {
    gf::Registry<Shape>::instance().create(o, {"model"});
    FAIL();
  } catch (const gf::CaseError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("did you mean 'square'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("one of: disc, square"), std::string::npos) << msg;
    EXPECT_NE(msg.find("r.yaml:2:16"), std::string::npos) << msg;
  }
}

TEST(Registry, DocumentationModeDocumentsEveryModel) {
  gf::Params doc = gf::Params::documentation();
  gf::Params s = doc.section({"shape"});
  gf::Registry<Shape>::instance().create(s, {"model"});
  bool side = false, radius = false;
  for (const auto& k : doc.documentedKeys()) {
    side |= k.path == "shape.side";
    radius |= k.path == "shape.radius";
  }
  EXPECT_TRUE(side && radius);
}

TEST(Parallel, SumIsReproducibleForAThreadCount) {
  const auto term = [](std::int64_t i) { return 1.0 / (1.0 + static_cast<double>(i)); };
  const double a = gf::parallelSum(1000003, term);
  const double b = gf::parallelSum(1000003, term);
  EXPECT_EQ(a, b);
  EXPECT_NEAR(a, std::log(1000003.0) + 0.5772156649, 1e-6);  // harmonic number ~ ln n + Euler-Mascheroni
}
