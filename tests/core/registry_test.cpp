#include <gtest/gtest.h>

#include <map>

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

namespace {
// Models that share keys: every feeder reads "name" (and a nested "food" choice), two of three
// read "bowl"; two of the three foods read "amount", each with its own default.
struct Food {
  virtual ~Food() = default;
};
struct Seeds : Food {
  explicit Seeds(gf::Params& p) { p.real({"amount", "g", "seeds: grams per day"}, 10.0); }
};
struct Worms : Food {
  explicit Worms(gf::Params& p) { p.real({"amount", "g", "worms: grams per day"}, 5.0); }
};
struct Nectar : Food {
  explicit Nectar(gf::Params& p) { p.real({"sugar", "-", "nectar: sugar mass fraction"}, 0.2); }
};
struct Feeder {
  virtual ~Feeder() = default;
};
struct FeederBase : Feeder {
  explicit FeederBase(gf::Params& p) {
    p.text({"name", "-", "name of the feeder"}, "feeder");
    gf::Params food = p.section({"food", "-", "what it holds"});
    gf::Registry<Food>::instance().create(food, {"kind", "-", "food kind"}, "seeds");
  }
};
struct Tray : FeederBase {
  explicit Tray(gf::Params& p) : FeederBase(p) { p.real({"bowl", "m", "tray: bowl diameter"}, 0.1); }
};
struct Tube : FeederBase {
  explicit Tube(gf::Params& p) : FeederBase(p) { p.real({"bowl", "m", "tube: bowl diameter"}, 0.1); }
};
struct Ball : FeederBase {
  explicit Ball(gf::Params& p) : FeederBase(p) { p.real({"mesh", "m", "ball: mesh size"}, 0.01); }
};
}  // namespace

GF_REGISTER_MODEL(Food, Seeds, "seeds", "seeds")
GF_REGISTER_MODEL(Food, Worms, "worms", "worms")
GF_REGISTER_MODEL(Food, Nectar, "nectar", "nectar")
GF_REGISTER_MODEL(Feeder, Tray, "tray", "a tray")
GF_REGISTER_MODEL(Feeder, Tube, "tube", "a tube")
GF_REGISTER_MODEL(Feeder, Ball, "ball", "a ball")

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

TEST(Registry, DocumentationSaysWhichModelsReadAKey) {
  gf::Params doc = gf::Params::documentation();
  gf::Params feeders = doc.list({"feeders"}).front();
  gf::Registry<Feeder>::instance().create(feeders, {"type"});
  std::map<std::string, gf::KeyDoc> keys;
  for (const auto& k : doc.documentedKeys()) keys[k.path] = k;
  // Read by every model, also a nested choice and what every model of it reads.
  EXPECT_EQ(keys.at("feeders[].name").help, "(all types) name of the feeder");
  EXPECT_EQ(keys.at("feeders[].food").help, "(all types) what it holds");
  EXPECT_EQ(keys.at("feeders[].food.kind").help, "(all types) food kind");
  // Read by some models: each of them named, each one's help given.
  EXPECT_EQ(keys.at("feeders[].bowl").help, "(type = tray, tube) tray: bowl diameter; tube: bowl diameter");
  EXPECT_EQ(keys.at("feeders[].mesh").help, "(type = ball) ball: mesh size");
  // Keys of the nested choice: labelled by it (whatever the feeder), with each model's default.
  EXPECT_EQ(keys.at("feeders[].food.amount").help, "(kind = seeds, worms) seeds: grams per day; worms: grams per day");
  EXPECT_EQ(keys.at("feeders[].food.amount").defaultValue, "10 (seeds), 5 (worms)");
  EXPECT_EQ(keys.at("feeders[].food.sugar").help, "(kind = nectar) nectar: sugar mass fraction");
  EXPECT_EQ(keys.at("feeders[].bowl").defaultValue, "0.1");
  // The choice key itself belongs to no model.
  EXPECT_EQ(keys.at("feeders[].type").help, "");
}

TEST(Parallel, SumIsReproducibleForAThreadCount) {
  const auto term = [](std::int64_t i) { return 1.0 / (1.0 + static_cast<double>(i)); };
  const double a = gf::parallelSum(1000003, term);
  const double b = gf::parallelSum(1000003, term);
  EXPECT_EQ(a, b);
  EXPECT_NEAR(a, std::log(1000003.0) + 0.5772156649, 1e-6);  // harmonic number ~ ln n + Euler-Mascheroni
}
