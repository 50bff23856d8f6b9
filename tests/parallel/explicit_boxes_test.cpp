// The explicit-box form of the ranks' layout (parallel/decomposition.hpp), in one process: the
// boxes of a recursive bisection tile the domain, ownership is one box per position (shared faces
// to the upper box, the domain's upper faces included), neighbours are the boxes within the
// reach (periodic images included), and boxes that do not tile are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>

#include "parallel/decomposition.hpp"
#include "domain_box.hpp"

namespace gf::parallel {
namespace {

using testing::box;

// A bisection of [0,1] x [0,1] x [0,2]: z cut at 0.5, the lower slab cut in x at 0.3, the upper
// one in y at 0.6, then the last box cut in x at 0.7 (boxes of unequal shapes, as RCB makes).
std::vector<Box> bisection() {
  return {{{0.0, 0.0, 0.0}, {0.3, 1.0, 0.5}},
          {{0.3, 0.0, 0.0}, {1.0, 1.0, 0.5}},
          {{0.0, 0.0, 0.5}, {1.0, 0.6, 2.0}},
          {{0.0, 0.6, 0.5}, {0.7, 1.0, 2.0}},
          {{0.7, 0.6, 0.5}, {1.0, 1.0, 2.0}}};
}

TEST(ExplicitBoxes, EveryPositionHasOneOwnerAndRanksAgree) {
  const Domain d = box({1.0, 1.0, 2.0});
  const std::vector<Box> boxes = bisection();
  const int n = static_cast<int>(boxes.size());
  std::vector<Decomposition> ranks;
  for (int r = 0; r < n; ++r) ranks.emplace_back(d, boxes, r, 0.05);
  EXPECT_TRUE(ranks[0].explicitBoxes());
  EXPECT_EQ(ranks[0].ranks(), n);
  EXPECT_EQ(ranks[0].describe(), "5 boxes");
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 x{u(random), u(random), 2.0 * u(random)};
    int holders = 0;
    for (int r = 0; r < n; ++r) {
      const Vec3 lo = ranks[0].lower(r), hi = ranks[0].upper(r);
      holders += x.x >= lo.x && x.x < hi.x && x.y >= lo.y && x.y < hi.y && x.z >= lo.z && x.z < hi.z;
    }
    ASSERT_EQ(holders, 1) << "the boxes tile the domain";
    const int owner = ranks[0].ownerOf(x);
    for (int r = 1; r < n; ++r) ASSERT_EQ(ranks[r].ownerOf(x), owner) << "every rank finds the same owner";
    const Vec3 dist = ranks[0].distanceToBox(x, owner);
    EXPECT_EQ(dist, (Vec3{0, 0, 0}));
  }
  // Shared faces belong to the upper box; the domain's upper faces to the box on them; positions
  // outside the domain to the box on the nearest face.
  EXPECT_EQ(ranks[0].ownerOf({0.3, 0.5, 0.25}), 1);
  EXPECT_EQ(ranks[0].ownerOf({0.5, 0.5, 0.5}), 2);
  EXPECT_EQ(ranks[0].ownerOf({1.0, 1.0, 2.0}), 4);
  EXPECT_EQ(ranks[0].ownerOf({0.1, 0.5, -0.3}), 0);
  EXPECT_EQ(ranks[0].ownerOf({0.9, 1.2, 2.5}), 4);
  // Box widths: the thinnest side that does not span the domain (0.3 of rank 0, x).
  EXPECT_NEAR(ranks[0].smallestBoxWidth(), 0.3, 1e-15);
  EXPECT_EQ(ranks[0].boxes().size(), boxes.size());
  EXPECT_FALSE(ranks[0].gridded());
}

// Boxes of a random recursive bisection of `box` into `parts` (cut axis and position at random).
void bisectAtRandom(const Box& box, int parts, std::mt19937& random, std::vector<Box>& out) {
  if (parts == 1) {
    out.push_back(box);
    return;
  }
  const int axis = static_cast<int>(random() % 3);
  const int lower = parts / 2;
  const double f = std::uniform_real_distribution<double>(0.2, 0.8)(random);
  const double cut = box.lower[axis] + f * (box.upper[axis] - box.lower[axis]);
  Box a = box, b = box;
  a.upper[axis] = cut;
  b.lower[axis] = cut;
  bisectAtRandom(a, lower, random, out);
  bisectAtRandom(b, parts - lower, random, out);
}

TEST(ExplicitBoxes, OwnershipByTheCutTreeMatchesTheBoxes) {
  // Many boxes of a bisection: the owner found down the cut tree is the box holding the position.
  const Domain d = box({1.0, 2.0, 3.0});
  std::mt19937 random(11);
  for (int parts : {2, 3, 7, 64, 100}) {
    std::vector<Box> boxes;
    bisectAtRandom({d.min, d.max}, parts, random, boxes);
    const Decomposition dec(d, boxes, 0);
    std::uniform_real_distribution<double> u(-0.05, 1.05);
    for (int k = 0; k < 3000; ++k) {
      Vec3 x{u(random), 2.0 * u(random), 3.0 * u(random)};
      if (k % 10 == 0) x = boxes[static_cast<std::size_t>(k) % boxes.size()].lower;  // on the faces
      Vec3 y = x;
      for (int a = 0; a < 3; ++a) y[a] = std::clamp(y[a], d.min[a], d.max[a]);
      int expected = -1;
      for (std::size_t r = 0; r < boxes.size() && expected < 0; ++r) {
        bool in = true;
        for (int a = 0; a < 3; ++a)
          in = in && y[a] >= boxes[r].lower[a] && (y[a] < boxes[r].upper[a] || boxes[r].upper[a] == d.max[a]);
        if (in) expected = static_cast<int>(r);
      }
      ASSERT_EQ(dec.ownerOf(x), expected) << parts << " boxes";
    }
  }
}

TEST(ExplicitBoxes, NeighboursAreTheBoxesWithinTheReach) {
  const Domain d = box({1.0, 1.0, 2.0});
  // Rank 0 touches 1 (face) and 2, 3 (across z = 0.5), but not 4 (0.4 away in x).
  Decomposition zero(d, bisection(), 0, 0.0);
  EXPECT_EQ(zero.neighbourRanks(), (std::vector<int>{1, 2, 3}));
  zero.setReach(0.45);
  EXPECT_EQ(zero.neighbourRanks(), (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(zero.reach(), 0.45);
  // Neighbours list each other.
  for (double reach : {0.0, 0.1, 0.45})
    for (int r = 0; r < 5; ++r) {
      const Decomposition a(d, bisection(), r, reach);
      for (int q : a.neighbourRanks()) {
        const Decomposition b(d, bisection(), q, reach);
        const auto& back = b.neighbourRanks();
        EXPECT_TRUE(std::find(back.begin(), back.end(), r) != back.end()) << r << " and " << q;
      }
    }
  // Sides: a face inside the domain is shared, a face on a wall physical.
  EXPECT_EQ(zero.side(0, -1), Side::Physical);
  EXPECT_EQ(zero.side(0, +1), Side::Shared);
  EXPECT_EQ(zero.side(2, +1), Side::Shared);
  EXPECT_EQ(zero.neighbourAcross(0, +1), -1);
}

TEST(ExplicitBoxes, PeriodicImagesCountForNeighboursAndDistances) {
  // Periodic x: rank 0's box [0, 0.3) and rank 4's [0.7, 1) meet across the periodic face (gap
  // 0.3 directly, 0 through the image).
  const Domain d = box({1.0, 1.0, 2.0}, {true, false, false});
  const std::vector<Box> boxes = {{{0.0, 0.0, 0.0}, {0.3, 1.0, 2.0}},
                                  {{0.3, 0.0, 0.0}, {0.7, 1.0, 2.0}},
                                  {{0.7, 0.0, 0.0}, {1.0, 1.0, 2.0}}};
  const Decomposition first(d, boxes, 0, 0.01);
  EXPECT_EQ(first.neighbourRanks(), (std::vector<int>{1, 2}));
  EXPECT_EQ(first.side(0, -1), Side::Shared);  // across the periodic face: rank 2
  EXPECT_NEAR(first.distanceToBox({0.98, 0.5, 1.0}, 0).x, 0.02, 1e-12);
  EXPECT_NEAR(first.distanceToBox({0.98, 0.5, 1.0}, 1).x, 0.28, 1e-12);
  // Bounded x: rank 2's box is 0.4 away from rank 0's.
  const Decomposition bounded(box({1.0, 1.0, 2.0}), boxes, 0, 0.01);
  EXPECT_EQ(bounded.neighbourRanks(), (std::vector<int>{1}));
  // One box spanning a periodic axis: its own image across that face.
  const Decomposition whole(d, {{{0, 0, 0}, {1.0, 1.0, 2.0}}}, 0, 0.01);
  EXPECT_EQ(whole.side(0, +1), Side::Periodic);
  EXPECT_TRUE(whole.neighbourRanks().empty());
  EXPECT_FALSE(whole.distributed());
}

TEST(ExplicitBoxes, BoxesThatDoNotTileAreRefused) {
  const Domain d = box({1.0, 1.0, 1.0});
  // A gap.
  EXPECT_THROW(Decomposition(d, {{{0, 0, 0}, {0.4, 1, 1}}, {{0.5, 0, 0}, {1, 1, 1}}}, 0), std::invalid_argument);
  // An overlap.
  EXPECT_THROW(Decomposition(d, {{{0, 0, 0}, {0.6, 1, 1}}, {{0.5, 0, 0}, {1, 1, 1}}}, 0), std::invalid_argument);
  // Outside the domain.
  EXPECT_THROW(Decomposition(d, {{{0, 0, 0}, {0.5, 1, 1}}, {{0.5, 0, 0}, {1.5, 1, 1}}}, 0), std::invalid_argument);
  // A rank without a box.
  EXPECT_THROW(Decomposition(d, {{{0, 0, 0}, {1, 1, 1}}}, 1), std::invalid_argument);
}

TEST(ExplicitBoxes, TheCartesianFormListsItsBoxes) {
  const Domain d = box({1.0, 1.0, 2.0});
  const Decomposition cartesian(d, {1, 1, 2}, 2, 1);
  const std::vector<Box> boxes = cartesian.boxes();
  ASSERT_EQ(boxes.size(), 2u);
  EXPECT_EQ(boxes[1].lower, (Vec3{0, 0, 1}));
  EXPECT_FALSE(cartesian.explicitBoxes());
  // Handed back as explicit boxes, they give the same owners.
  const Decomposition same(d, boxes, 1);
  for (const Vec3& x : {Vec3{0.5, 0.5, 0.2}, Vec3{0.5, 0.5, 1.0}, Vec3{1.0, 1.0, 2.0}, Vec3{0.0, 0.0, 0.99}})
    EXPECT_EQ(same.ownerOf(x), cartesian.ownerOf(x));
  EXPECT_EQ(same.neighbourRanks(), cartesian.neighbourRanks());
}

}  // namespace
}  // namespace gf::parallel
