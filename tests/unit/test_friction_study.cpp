// The friction study (thesis Fig. 4.6) on a short segment length: every configuration asked
// for gets one row per speed of the grid, the grid holds the thesis's speeds, and
// an unknown configuration is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../cli_helpers.hpp"
#include "app/friction_study.hpp"
#include "io/scene.hpp"
#include "io/segments_csv.hpp"
#include "io/settings.hpp"

namespace bkq {
namespace {

TEST(FrictionStudy, ShippedBrakeScenesLoadAndValidate) {
  const std::string dir = BKQUAKE_SOURCE_DIR "/data/scenes/brake/";
  for (const char* name :
       {"bkp", "bk", "1dof", "special-1dof", "bkp-descent", "bkp-ascent", "bkp-descent-linear"}) {
    const Scene s = Scene::from_file(dir + name + ".ini");
    EXPECT_NO_THROW(s.validate()) << name;
    EXPECT_EQ(s.choice("drive.mode"), "continuous") << name;
  }
  // The 1DOF reading: one body of the pad's mass (= the blocks' total) on the caliper spring
  // with the pad's damping ratio, feeling the friction of all N blocks.
  const ModelParams one = model_from_scene(Scene::from_file(dir + "1dof.ini"));
  const ModelParams bkp = model_from_scene(Scene::from_file(dir + "bkp.ini"));
  EXPECT_DOUBLE_EQ(one.m_u, bkp.m_x);
  EXPECT_DOUBLE_EQ(one.m_u, bkp.n * bkp.m_u);
  EXPECT_DOUBLE_EQ(one.k_p, bkp.k_p0);
  EXPECT_NEAR(one.c_u, critical_damping(1.0 / 12, bkp.k_p0, bkp.m_x), 1e-9);
  EXPECT_DOUBLE_EQ(one.threshold(), bkp.n * bkp.threshold());
}

TEST(FrictionStudy, GridHoldsTheThesisSpeeds) {
  std::vector<double> speeds;
  for (const StudyRun& r : study_grid())
    for (int k = 0; k < r.count; ++k) speeds.push_back(r.v0 + k * r.inc);
  auto has = [&](double v) {
    for (double s : speeds)
      if (std::abs(s - v) < 1e-9) return true;
    return false;
  };
  for (double v : {0.005, 0.045, 0.05, 0.055, 0.06, 0.065, 0.08, 0.09, 0.1, 0.11, 0.12,
                   0.16,  0.17,  0.18, 0.19,  0.28, 0.5,   0.88, 0.89, 0.9, 0.91, 1.0})
    EXPECT_TRUE(has(v)) << v;
  ASSERT_EQ(study_grid().size(), 5u);
  EXPECT_LT(study_grid()[0].inc, study_grid()[3].inc);  // finer at low speeds
}

TEST(FrictionStudy, ShortStudyOfTheOneDofWritesEveryGridSpeed) {
  test::TempDir dir;
  const std::string out = dir.file("study");
  auto r = test::run_bkquake({"friction-study", "--scenes", BKQUAKE_SOURCE_DIR "/data/scenes/brake",
                              "--configs", "1dof", "--segment", "10", "--out", out, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto cols = read_numeric_columns(
      out + "/friction_study.csv", {"speed", "friction_mean", "friction_amp", "friction_law"});
  std::size_t expected = 0;
  for (const StudyRun& g : study_grid()) expected += static_cast<std::size_t>(g.count);
  ASSERT_EQ(cols[0].size(), expected);
  EXPECT_NEAR(cols[0].front(), 0.005, 1e-12);
  EXPECT_NEAR(cols[0].back(), 1.0, 1e-9);
  // The law column is the Table 3.1 law on the whole pad, N m_u phi(v) = 100 phi(v).
  for (std::size_t i = 0; i < cols[0].size(); ++i) {
    EXPECT_NEAR(cols[3][i], 100 * 0.99 / (1 + cols[0][i] / 0.99), 1e-9);
    EXPECT_TRUE(std::isfinite(cols[1][i]) && cols[2][i] >= 0);
  }
  r = test::run_bkquake({"friction-study", "--configs", "bkp,2dof", "--out", out});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("unknown configuration '2dof'"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace bkq
