// Rate-and-state scenes whose blocks differ: `bkquake stability` of per-block laws (rsf.blocks,
// rsf.pattern) answers with the dense linearisation (app/rsf_stability.hpp), never block 0's
// law, and refuses above its size limit; model.coupling_stiffness_y sets a lattice's springs
// across strike (auto: those along), and with none the rows move as uncoupled chains.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "../refusal.hpp"
#include "engine/rsf_cycle.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"
#include "stats/rsf_stability.hpp"

namespace bkq {
namespace {

using test::expect_refused;
using test::read_file;
using test::run_bkquake;

const std::string kScenes = std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/rsf/";

// The field `col` (0-based) of a two-line CSV's data row.
std::string field(const std::string& csv, int col) {
  std::string row = csv.substr(csv.find('\n') + 1);
  for (int i = 0; i < col; ++i) row = row.substr(row.find(',') + 1);
  return row.substr(0, row.find_first_of(",\n"));
}

TEST(RsfPerBlock, StabilityOfPerBlockLawsIsTheDenseLinearisation) {
  for (const char* name : {"chain-asperities.ini", "lattice-patches.ini"}) {
    test::TempDir tmp;
    const auto r = run_bkquake({"stability", kScenes + name, "--out", tmp.file("st")});
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("per-block laws"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("k_crit = sigma (b - a)/D_c ="), std::string::npos) << r.out;
    const std::string summary = read_file(tmp.file("st/rsf_stability.csv"));
    for (int col = 3; col <= 6; ++col) EXPECT_EQ(field(summary, col), "nan") << summary;
    EXPECT_NE(read_file(tmp.file("st/stability.csv")).find(",dense 0,"), std::string::npos);
    // The largest growth rate is the dense linearisation's, not block 0's modal analysis.
    const RsfModel m = settings_from_scene(Scene::from_file(kScenes + name)).rsf.chain;
    ASSERT_FALSE(rsf_homogeneous(m));
    const double growth = rsf_dense_eigenvalues(m)[0].real();
    EXPECT_NEAR(std::stod(field(summary, 9)), growth, 1e-9 * std::fabs(growth)) << name;
    const double block0 = rsf_eigenvalues(m, m.k)[0].real();
    EXPECT_GT(std::fabs(block0 - growth), 1e-3 * std::fabs(growth)) << name;
  }
}

TEST(RsfPerBlock, StabilityRefusesPerBlockLawsAboveTheDenseLimit) {
  test::TempDir tmp;
  expect_refused(
      run_bkquake({"stability", kScenes + "lattice-patches.ini", "--set", "model.blocks=100",
                   "--set", "model.rows=11", "--out", tmp.file("st")}),
      {"rsf.pattern", "1100 blocks", "at most 1000"});
  // One law for all: the modal analysis, any size.
  const auto r = run_bkquake({"stability", kScenes + "lattice-patches.ini", "--set",
                              "model.blocks=100", "--set", "model.rows=11", "--set",
                              "rsf.pattern=uniform", "--out", tmp.file("st2")});
  EXPECT_EQ(r.status, 0) << r.out << r.err;
}

// QDYN's block (qdyn-stickslip.ini) on a 6 x `rows` grid with k_c = 1e9 Pa/m, plus `extra`
// lines in [model].
Scene grid_scene(int blocks, int rows, const std::string& extra) {
  return Scene::from_text(
      "[model]\nkind = bk\nparameterisation = si\nblocks = " + std::to_string(blocks) +
          "\nrows = " + std::to_string(rows) + "\nstiffness = 2e9\ncoupling_stiffness = 1e9\n" +
          extra +
          "\n[friction]\nlaw = rsf\n[rsf]\na = 0.01\nb = 0.025\ndc = 1e-5\nv_init = 1e-6\n"
          "[drive]\nmode = continuous\nspeed = 1e-6\n",
      "test");
}
RsfModel lattice(const std::string& extra, int rows = 3) {
  Scene s = grid_scene(6, rows, extra);
  s.validate();
  return settings_from_scene(s).rsf.chain;
}

TEST(RsfPerBlock, AcrossStrikeStiffnessKey) {
  // auto: the springs across strike are those along it, as before the key.
  const RsfModel same = lattice("");
  ASSERT_EQ(same.springs.size(), 2u);
  EXPECT_EQ(same.springs[0].k, 1e9);
  EXPECT_EQ(same.springs[1].dy, 1);
  EXPECT_EQ(same.springs[1].k, 1e9);
  const RsfModel weak = lattice("coupling_stiffness_y = 3e7");
  ASSERT_EQ(weak.springs.size(), 2u);
  EXPECT_EQ(weak.springs[0].k, 1e9);
  EXPECT_EQ(weak.springs[1].k, 3e7);
  // A column (model.blocks = 1) is the chain across strike: its springs are k_c_y.
  Scene col = grid_scene(1, 5, "coupling_stiffness_y = 4e8");
  col.validate();
  const RsfModel c = settings_from_scene(col).rsf.chain;
  ASSERT_EQ(c.stencil().size(), 1u);
  EXPECT_EQ(c.stencil()[0].dy, 1);
  EXPECT_EQ(c.stencil()[0].k, 4e8);
  // A chain has no across-strike spring.
  test::TempDir tmp;
  expect_refused(run_bkquake({"stability", kScenes + "qdyn-stickslip.ini", "--set",
                              "model.coupling_stiffness_y=1e9", "--out", tmp.file("st")}),
                 {"model.coupling_stiffness_y", "model.rows"});
}

// With no springs across strike the rows are uncoupled chains: each row, started as it is,
// keeps the cycle of a chain started the same way (the step sequence differs, so to the
// tolerance, not bit for bit).
TEST(RsfPerBlock, NoAcrossStrikeSpringsGiveUncoupledRows) {
  const int nx = 6, rows = 3;
  const RsfModel l = lattice("coupling_stiffness_y = 0", rows);
  RsfModel chain = lattice("", 1);
  ASSERT_EQ(l.springs.size(), 1u);
  ASSERT_EQ(chain.rows, 1);
  std::vector<double> v(nx * rows);
  for (int j = 0; j < nx * rows; ++j)
    v[j] = 1e-6 * (1 + 0.5 * std::sin(1.3 * (j % nx) + 0.9 * (j / nx) + 0.2 * j * j));
  RsfCycle a(l, 1e-10, v, {10});
  a.advance_to(2000);
  for (int y = 0; y < rows; ++y) {
    const std::vector<double> row(v.begin() + y * nx, v.begin() + (y + 1) * nx);
    RsfCycle b(chain, 1e-10, row, {10});
    b.advance_to(2000);
    for (int x = 0; x < nx; ++x) {
      EXPECT_NEAR(a.ln_v(y * nx + x), b.ln_v(x), 1e-5) << "row " << y << " block " << x;
      EXPECT_NEAR(a.slip(y * nx + x) / b.slip(x), 1, 1e-7) << "row " << y << " block " << x;
    }
  }
  // With the springs across strike the rows pull on each other: not the chain's cycle.
  RsfCycle coupled(lattice("", rows), 1e-10, v, {10});
  coupled.advance_to(2000);
  RsfCycle b(chain, 1e-10, std::vector<double>(v.begin(), v.begin() + nx), {10});
  b.advance_to(2000);
  EXPECT_GT(std::fabs(coupled.slip(0) / b.slip(0) - 1), 1e-4);
}

}  // namespace
}  // namespace bkq
