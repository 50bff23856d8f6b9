#include <gtest/gtest.h>

#include "core/params.hpp"

using gf::CaseError;
using gf::Params;
using gf::Range;

TEST(Params, ReadsValuesAndDefaults) {
  Params p = Params::loadString("a: 2.5\nb: [1, 2, 3]\nsub:\n  n: 4\n", "t.yaml");
  EXPECT_DOUBLE_EQ(p.real({"a", "m"}), 2.5);
  EXPECT_DOUBLE_EQ(p.real({"missing", "m"}, 7.0), 7.0);
  EXPECT_EQ(p.vec3({"b", "m"}).z, 3.0);
  Params sub = p.section({"sub"});
  EXPECT_EQ(sub.integer({"n"}), 4);
  EXPECT_NO_THROW(p.checkUnknownKeys());
}

TEST(Params, RangeViolationNamesLineKeyAndExpectation) {
  Params p = Params::loadString("x: 1\nparticles:\n  diameter: -0.002\n", "case.yaml");
  Params s = p.section({"particles"});
  try {
    s.real({"diameter", "m", "", Range::positive()});
    FAIL() << "no error";
  } catch (const CaseError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("case.yaml:3:13"), std::string::npos) << msg;
    EXPECT_NE(msg.find("particles.diameter"), std::string::npos) << msg;
    EXPECT_NE(msg.find("> 0"), std::string::npos) << msg;
  }
}

TEST(Params, UnknownKeySuggestsClosest) {
  Params p = Params::loadString("densty: 2500\n", "c.yaml");
  p.real({"density", "kg/m^3"}, 1000.0);
  try {
    p.checkUnknownKeys();
    FAIL() << "no error";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'density'"), std::string::npos) << e.what();
  }
}

TEST(Params, DocumentationModeRecordsKeys) {
  Params p = Params::documentation();
  Params s = p.section({"time", "-", "time stepping"});
  s.real({"end", "s", "end time", Range::nonNegative()});
  auto docs = p.documentedKeys();
  ASSERT_EQ(docs.size(), 2u);
  EXPECT_EQ(docs[1].path, "time.end");
  EXPECT_EQ(docs[1].unit, "s");
}
