// The shipped lattice scenes (data/scenes/lattice/: BK, and the OFC automaton's with ofc in
// the file name): each says in its header what it is
// for and how long it takes, reads as a lattice (model.rows > 1), and runs a few events (or
// time units) from the command line as users run it. Among them are a nearest-neighbour
// lattice, a lattice with 1/r^3 springs (Mori & Kawamura's elastic kernel) and a continuous
// one that writes blocks.csv for the stress field of analysis/plot_lattice.py.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(LatticeScenes, EachShippedSceneSaysWhatItIsAndRunsBriefly) {
  const fs::path dir = fs::path(BKQUAKE_SOURCE_DIR) / "data" / "scenes" / "lattice";
  std::vector<fs::path> scenes;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".ini") scenes.push_back(e.path());
  std::sort(scenes.begin(), scenes.end());
  ASSERT_GE(scenes.size(), 3u);
  int nearest = 0, power3 = 0, continuous = 0, ofc = 0, relaxation = 0;
  test::TempDir tmp;
  for (const fs::path& scene : scenes) {
    const std::string name = scene.filename().string();
    const std::string text = test::read_file(scene.string());
    // The header comment: what the scene is for and roughly how long it takes.
    EXPECT_EQ(text.rfind("#", 0), 0u) << name;
    EXPECT_TRUE(has(text, "What it is for")) << name;
    EXPECT_TRUE(has(text, "Time: about")) << name;
    const bool cont = has(text, "mode = continuous");
    std::vector<std::string> args = {"run", scene.string(), "--quiet", "--out", tmp.file(name)};
    const std::vector<std::string> brief =
        cont ? std::vector<std::string>{"run.duration=40"}
             : std::vector<std::string>{"run.events=200", "run.transient_events=0"};
    for (const std::string& s : brief) args.insert(args.end(), {"--set", s});
    const auto r = test::run_bkquake(args);
    ASSERT_EQ(r.status, 0) << name << ": " << r.err;
    const std::string effective = test::read_file(tmp.file(name) + "/scene.ini");
    // The automaton's scenes (ofc in the file name) beside the BK lattice's.
    if (has(name, "ofc")) {
      EXPECT_TRUE(has(effective, "\nkind = ofc")) << name;
      EXPECT_TRUE(has(test::read_file(tmp.file(name) + "/catalog.csv"), ",trigger_row")) << name;
      ofc += 1;
      relaxation += has(effective, "\nrelaxation_time = 0.001");
      continue;
    }
    EXPECT_TRUE(has(effective, "\nkind = bk")) << name;
    EXPECT_FALSE(has(effective, "\nrows = 1\n")) << name;
    const std::string catalog = test::read_file(tmp.file(name) + "/catalog.csv");
    EXPECT_TRUE(has(catalog, ",trigger_row,first_row,last_row")) << name;
    if (cont) {
      EXPECT_TRUE(fs::exists(tmp.file(name) + "/blocks.csv")) << name;
      ++continuous;
    } else {
      EXPECT_EQ(std::count(catalog.begin(), catalog.end(), '\n'), 201) << name;
      nearest += has(effective, "\ncoupling = nearest");
      power3 += has(effective, "\ncoupling = power") && has(effective, "\ncoupling_exponent = 3");
    }
  }
  EXPECT_GE(nearest, 1);
  EXPECT_GE(power3, 1);
  EXPECT_GE(continuous, 1);
  EXPECT_GE(ofc, 2);
  EXPECT_GE(relaxation, 1);
}

}  // namespace
}  // namespace bkq
