// Sweep files: lists and ranges expand as documented (both ends exact, log spacing), every
// swept value is checked against the parameter table, product and zip give the points in
// the stated order, and replica seeds depend on the point and replica only.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <set>
#include <string>

#include "app/sweep.hpp"
#include "app/sweep_comm.hpp"
#include "core/error.hpp"
#include "io/sweep_file.hpp"

namespace bkq {
namespace {

std::string error_of(const std::string& text, const std::vector<std::string>& sets = {}) {
  try {
    parse_sweep(text, "t.ini", "", sets);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(SweepFile, ListsAndRangesExpand) {
  EXPECT_EQ(expand_sweep_values("friction.alpha", "1, 2,2.5 , 3"),
            (std::vector<std::string>{"1", "2", "2.5", "3"}));
  const auto lin = expand_sweep_values("drive.speed", "0.005:1:200");
  ASSERT_EQ(lin.size(), 200u);
  EXPECT_EQ(lin.front(), "0.005");
  EXPECT_EQ(lin.back(), "1");
  EXPECT_NEAR(std::strtod(lin[1].c_str(), nullptr), 0.005 + 0.995 / 199, 1e-15);
  const auto lg = expand_sweep_values("drive.speed", "log:0.005:1:50");
  ASSERT_EQ(lg.size(), 50u);
  EXPECT_EQ(lg.front(), "0.005");
  EXPECT_EQ(lg.back(), "1");
  // Log spacing: a constant ratio between neighbours.
  const double r1 = std::strtod(lg[1].c_str(), nullptr) / 0.005;
  const double r2 = std::strtod(lg[30].c_str(), nullptr) / std::strtod(lg[29].c_str(), nullptr);
  EXPECT_NEAR(r1, r2, 1e-12);
  EXPECT_NEAR(r1, std::pow(200.0, 1.0 / 49), 1e-12);
}

TEST(SweepFile, BadRangesAndValuesNameTheKey) {
  EXPECT_NE(error_of("[vary]\ndrive.speed = log:0:1:5\n").find("drive.speed"), std::string::npos);
  EXPECT_NE(error_of("[vary]\ndrive.speed = 0:1\n").find("lo:hi:count"), std::string::npos);
  EXPECT_NE(error_of("[vary]\ndrive.speed = 0:1:x\n").find("count 'x'"), std::string::npos);
  // Checked against the parameter table: sigma must be in [0, 1).
  const std::string e = error_of("[vary]\nfriction.sigma = 0.01, 1.5\n");
  EXPECT_NE(e.find("friction.sigma"), std::string::npos) << e;
  EXPECT_NE(e.find("1.5"), std::string::npos) << e;
  EXPECT_NE(error_of("[vary]\nfriction.nonsense = 1, 2\n").find("not a scene key"),
            std::string::npos);
  EXPECT_NE(error_of("[sweep]\nreplicas = 0\n[vary]\nfriction.alpha = 1\n").find("replicas"),
            std::string::npos);
  EXPECT_NE(error_of("[vary]\nfriction.alpha = 1, 1.0\n").find("comes twice"), std::string::npos);
  EXPECT_NE(error_of("[sweep]\ncombine = zip\n[vary]\nfriction.alpha = 1, 2\nmodel.blocks = 10\n")
                .find("zip"),
            std::string::npos);
  EXPECT_NE(error_of("[sweep]\n").find("nothing to sweep"), std::string::npos);
  EXPECT_NE(error_of("[other]\nx = 1\n").find("unknown section"), std::string::npos);
  EXPECT_NE(error_of("[vary]\nfriction.alpha = 1, 2\n[set]\nfriction.alpha = 3\n")
                .find("both in [set] and in [vary]"),
            std::string::npos);
  // --set goes through the same table.
  EXPECT_NE(error_of("[vary]\nfriction.alpha = 1, 2\n", {"run.events=-1"}).find("run.events"),
            std::string::npos);
  EXPECT_EQ(error_of("[vary]\nfriction.alpha = 1, 2\n", {"run.events=10"}), "");
}

TEST(SweepFile, ProductAndZipOrder) {
  const SweepSpec prod =
      parse_sweep("[vary]\nfriction.alpha = 1, 2\nmodel.blocks = 10:30:3\n[set]\nrun.events = 7\n",
                  "t.ini", "", {"run.transient_events=3"});
  const auto pts = prod.points();
  ASSERT_EQ(pts.size(), 6u);
  EXPECT_EQ(pts[0].values[0].second, "1");
  EXPECT_EQ(pts[0].values[1].second, "10");
  EXPECT_EQ(pts[1].values[1].second, "20");  // the last key varies fastest
  EXPECT_EQ(pts[3].values[0].second, "2");
  EXPECT_EQ(pts[3].values[1].second, "10");
  EXPECT_EQ(pts[5].scene.integer("model.blocks"), 30);
  EXPECT_EQ(pts[5].scene.real("friction.alpha"), 2.0);
  EXPECT_EQ(pts[5].scene.integer("run.events"), 7);
  EXPECT_EQ(pts[5].scene.integer("run.transient_events"), 3);

  const SweepSpec zip = parse_sweep(
      "[sweep]\ncombine = zip\n[vary]\nfriction.alpha = 1, 2, 3\nmodel.blocks = 10, 20, 30\n",
      "t.ini", "", {});
  const auto z = zip.points();
  ASSERT_EQ(z.size(), 3u);
  EXPECT_EQ(z[2].scene.real("friction.alpha"), 3.0);
  EXPECT_EQ(z[2].scene.integer("model.blocks"), 30);
}

TEST(SweepFile, CollectChoosesWhatReplicasKeep) {
  const SweepSpec s = parse_sweep(
      "[sweep]\ncollect = histogram, summary\n[vary]\nfriction.alpha = 1\n", "t.ini", "", {});
  EXPECT_FALSE(s.keep_catalog);
  EXPECT_TRUE(s.keep_histogram);
  EXPECT_NE(
      error_of("[sweep]\ncollect = everything\n[vary]\nfriction.alpha = 1\n").find("everything"),
      std::string::npos);
}

TEST(SweepSeeds, DependOnPointAndReplicaOnlyAndAreDistinct) {
  std::set<std::uint64_t> seen;
  for (std::size_t p = 0; p < 50; ++p)
    for (int r = 0; r < 4; ++r) EXPECT_TRUE(seen.insert(sweep_seed(1000, false, p, 4, r)).second);
  EXPECT_EQ(sweep_seed(1000, false, 0, 4, 0), 1000u);  // point 0, replica 0: the scene's seed
  EXPECT_EQ(sweep_seed(1000, false, 3, 4, 2), 1014u);
  EXPECT_EQ(sweep_seed(1000, true, 3, 4, 2), 1002u);  // run.seed swept: the point's seed + r
  // Stays a valid run.seed (below 2^63).
  EXPECT_LT(sweep_seed(~std::uint64_t{0} >> 1, false, 5, 2, 1), std::uint64_t{1} << 63);
}

TEST(SweepComm, LauncherSizeFromTheEnvironment) {
  const char* keep = std::getenv("OMPI_COMM_WORLD_SIZE");
  const std::string saved = keep ? keep : "";
  ::setenv("OMPI_COMM_WORLD_SIZE", "3", 1);
  EXPECT_EQ(launcher_world_size(), 3);
  if (keep)
    ::setenv("OMPI_COMM_WORLD_SIZE", saved.c_str(), 1);
  else
    ::unsetenv("OMPI_COMM_WORLD_SIZE");
}

}  // namespace
}  // namespace bkq
