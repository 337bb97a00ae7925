// The friction-law registry (model/law_list.hpp, model/friction_laws.hpp): every law is
// found by its keyword, its flags reach the run-time table, and its phi(y) is the formula
// of SPEC §1 (eqs. 3.5, 2.9, 2.3).
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "model/chain.hpp"
#include "model/friction_laws.hpp"

namespace bkq {
namespace {

ModelParams params_with(FrictionLaw law) {
  ModelParams p;
  p.law = law;
  p.m_u = 2;
  p.F0 = 1.5;
  p.sigma = 0.1;
  p.v_c = 0.25;
  p.table = FrictionTable{{0.1, 1.0}, {0.8, 0.5}};  // for the table law
  return p;
}

TEST(FrictionLaws, EveryKeywordNamesItsLawAndBack) {
  const auto names = law_names();
  ASSERT_EQ(static_cast<int>(names.size()), law::All::size);
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size());
  for (const std::string& name : names) {
    const auto id = law_named(name);
    ASSERT_TRUE(id.has_value()) << name;
    EXPECT_EQ(law_name(*id), name);
    EXPECT_STREQ(to_string(*id), name.c_str());
  }
  EXPECT_FALSE(law_named("thesis2").has_value());
  EXPECT_EQ(law_named("clst91"), law_id<law::Clst91>);
  EXPECT_EQ(ModelParams().law, law_id<law::Clst91>);  // the default law
}

TEST(FrictionLaws, RunTimeFlagsAreTheLawsOwn) {
  EXPECT_TRUE(law_traits(law_id<law::Thesis>).backslip);
  EXPECT_FALSE(law_traits(law_id<law::Clst91>).backslip);
  EXPECT_TRUE(law_traits(law_id<law::None>).frictionless);
  EXPECT_FALSE(law_traits(law_id<law::Cl89>).frictionless);
  EXPECT_FALSE(law_traits(law_id<law::Cl89>).drives_events);
  EXPECT_TRUE(law_traits(law_id<law::Thesis>).drives_events);
  for (int i = 0; i < law::All::size; ++i) {
    const ModelParams p = params_with(FrictionLaw{i});
    const Friction fr = friction_of(p);
    EXPECT_EQ(fr.backslip, law_traits(p.law).backslip) << to_string(p.law);
    EXPECT_EQ(fr.threshold, law_traits(p.law).frictionless ? -1.0 : p.F0 * p.m_u);
  }
}

TEST(FrictionLaws, MagnitudesAreTheFormulasOfSpec1) {
  const ModelParams p = params_with(law_id<law::Thesis>);
  const double k = p.F0 * (1 - p.sigma), scale = (1 - p.sigma) * p.v_c;
  for (double y : {0.0, 0.01, 0.3, -0.3, 5.0}) {
    EXPECT_NEAR(law::Thesis(p).magnitude(y), k / (1 + std::abs(y) / scale), 1e-15) << y;
    EXPECT_NEAR(law::Clst91(p).magnitude(y), k / (1 + std::max(y, 0.0) / scale), 1e-15) << y;
    EXPECT_NEAR(law::Cl89(p).magnitude(y), p.F0 / (1 + std::abs(y) / p.v_c), 1e-15) << y;
    EXPECT_EQ(law::None(p).magnitude(y), 0.0);
  }
}

TEST(FrictionLaws, TheForceOnASlidingBlockOpposesItsDirection) {
  for (FrictionLaw id : {law_id<law::Thesis>, law_id<law::Clst91>, law_id<law::None>}) {
    ModelParams p = params_with(id);
    p.n = 1;
    const ChainForces forces(p);
    const double w[1] = {0}, dir_plus[1] = {1}, dir_minus[1] = {-1}, mobile[1] = {1};
    const SubstrateState sub;
    const Range all[1] = {Range{0, 1}};
    for (double y : {0.2, -0.2}) {
      const double wd[1] = {y};
      double a = 0;
      const double* dir = y > 0 ? dir_plus : dir_minus;
      forces.block_accelerations(w, wd, mobile, dir, 0.0, 0.0, sub, all, &a);
      const double expected = law_traits(id).frictionless ? 0.0
                              : !law_traits(id).backslip
                                  ? -law::Clst91(p).magnitude(y)
                                  : -std::copysign(law::Thesis(p).magnitude(y), y);
      EXPECT_DOUBLE_EQ(a, expected) << to_string(id) << " y " << y;
    }
  }
}

}  // namespace
}  // namespace bkq
