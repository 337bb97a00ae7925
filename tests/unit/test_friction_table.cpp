// The tabulated friction law (friction.law = table; model/laws/table.hpp) and its file
// (io/friction_table): the law is odd, reproduces its rows, holds its first value below
// the first speed, is continuous where the scaled thesis law takes over, and a table of
// the thesis law drives a run as the thesis law does. Bad files are one-line errors
// naming the file and the line, exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "cli_helpers.hpp"
#include "core/error.hpp"
#include "integrate/stepper.hpp"
#include "io/friction_table.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"
#include "model/friction_laws.hpp"

namespace bkq {
namespace {

ModelParams table_params(std::vector<double> speed, std::vector<double> friction) {
  ModelParams p;
  p.law = law_id<law::Table>;
  p.F0 = 1;
  p.sigma = 0.01;
  p.v_c = 1;
  p.table = FrictionTable{std::move(speed), std::move(friction)};
  return p;
}

// A table ending at y = 1 (the thesis runs' range), not monotone on purpose.
ModelParams sample_params() {
  return table_params({0.005, 0.1, 0.3, 0.5, 1.0}, {0.9, 0.7, 0.75, 0.6, 0.5});
}

TEST(TableLaw, ReproducesItsRowsAndInterpolatesBetweenThem) {
  const ModelParams p = sample_params();
  const law::Table law(p);
  for (std::size_t i = 0; i < p.table.speed.size(); ++i)
    EXPECT_EQ(law.magnitude(p.table.speed[i]), p.table.friction[i]) << i;
  EXPECT_DOUBLE_EQ(law.magnitude(0.2), 0.725);
  EXPECT_DOUBLE_EQ(law.magnitude(0.75), 0.55);
}

TEST(TableLaw, HoldsItsFirstValueBelowTheFirstSpeed) {
  const law::Table law(sample_params());
  for (double y : {0.0, 1e-12, 0.001, 0.004999}) {
    EXPECT_EQ(law.magnitude(y), 0.9) << y;
    EXPECT_EQ(law.magnitude(-y), 0.9) << y;
  }
  EXPECT_EQ(law.threshold, 1.0);  // F0 m_u holds a block at y = 0
  EXPECT_TRUE(law::Table::backslip);
}

TEST(TableLaw, IsOdd) {
  ModelParams p = sample_params();
  p.n = 1;
  const ChainForces forces(p);
  const double w[1] = {0}, mobile[1] = {1};
  const SubstrateState sub;
  const Range all[1] = {Range{0, 1}};
  for (double y : {0.001, 0.05, 0.2, 0.3, 0.9, 1.0, 1.7, 40.0}) {
    const double wd_plus[1] = {y}, wd_minus[1] = {-y}, dir_plus[1] = {1}, dir_minus[1] = {-1};
    double a_plus = 0, a_minus = 0;
    forces.block_accelerations(w, wd_plus, mobile, dir_plus, 0.0, 0.0, sub, all, &a_plus);
    forces.block_accelerations(w, wd_minus, mobile, dir_minus, 0.0, 0.0, sub, all, &a_minus);
    EXPECT_LT(a_plus, 0.0) << y;
    EXPECT_EQ(a_plus, -a_minus) << y;
  }
}

TEST(TableLaw, IsContinuousWhereTheScaledThesisLawTakesOver) {
  const ModelParams p = sample_params();  // ends at |y| = 1
  const law::Table law(p);
  const law::Thesis thesis(p);
  const double end = law.magnitude(1.0);
  for (double h : {1e-6, 1e-9, 1e-12}) {
    EXPECT_NEAR(law.magnitude(1.0 + h), end, 1e-6 * h / 1e-6 + 1e-15) << h;
    EXPECT_NEAR(law.magnitude(1.0 - h), end, 1e-6 * h / 1e-6 + 1e-15) << h;
  }
  // Beyond the table: the thesis law scaled to meet the last row.
  for (double y : {1.5, 3.0, 100.0})
    EXPECT_NEAR(law.magnitude(y), thesis.magnitude(y) * 0.5 / thesis.magnitude(1.0), 1e-15) << y;
  EXPECT_NEAR(law.magnitude(-3.0), law.magnitude(3.0), 0.0);
}

// The lookup of the row below a speed goes through an index of uniform buckets (so its cost
// does not grow with the rows); it must find the same row, and so the same bits, as a
// binary search over all rows, the lookup it replaced. Tables evenly, unevenly and
// log-spaced, with rows that crowd into one bucket, of 2 to 10^5 rows; speeds at every
// row, one ulp either side, at the bucket edges and at random.
double reference_magnitude(const ModelParams& p, const law::Table& law, double y) {
  const std::vector<double>& s = p.table.speed;
  const std::vector<double>& f = p.table.friction;
  const double a = std::abs(y);
  if (!(a <= s.back())) return law.magnitude(y);  // beyond the table: no row lookup
  if (a <= s.front()) return f.front();
  const auto hi = std::upper_bound(s.begin(), s.end(), a);
  const std::size_t i = static_cast<std::size_t>(hi - s.begin()) - 1;
  if (i + 1 == s.size()) return f.back();
  const double t = (a - s[i]) / (s[i + 1] - s[i]);
  return f[i] + t * (f[i + 1] - f[i]);
}

TEST(TableLaw, ItsIndexedLookupGivesTheBinarySearchsBitsExactly) {
  std::mt19937_64 rng(20261126);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::vector<double>> tables;
  for (std::size_t n : {2, 7, 8, 9, 10, 100, 1000, 100000}) {
    std::vector<double> even, log_spaced, random_gaps, crowded;
    double x = 0;
    for (std::size_t i = 0; i < n; ++i) {
      even.push_back(static_cast<double>(i) / static_cast<double>(n - 1));
      log_spaced.push_back(1e-6 *
                           std::pow(1e7, static_cast<double>(i) / static_cast<double>(n - 1)));
      x += 1e-3 + unit(rng) * unit(rng) * unit(rng);
      random_gaps.push_back(x);
      // All rows but the last within 1e-9 of 0.3: they fall into one or two buckets.
      crowded.push_back(i + 1 == n ? 5.0
                                   : 0.3 + 1e-9 * static_cast<double>(i) / static_cast<double>(n));
    }
    for (auto* t : {&even, &log_spaced, &random_gaps, &crowded}) tables.push_back(*t);
  }
  std::size_t compared = 0;
  for (const std::vector<double>& speed : tables) {
    std::vector<double> friction;
    for (std::size_t i = 0; i < speed.size(); ++i) friction.push_back(0.5 + 0.4 * unit(rng));
    friction.front() = 0.9;
    const ModelParams p = table_params(speed, friction);
    const law::Table law(p);
    std::vector<double> ys;
    const std::size_t step = std::max<std::size_t>(1, speed.size() / 2000);
    for (std::size_t i = 0; i < speed.size(); i += step)
      for (double y : {speed[i], std::nextafter(speed[i], 0.0), std::nextafter(speed[i], 10.0)})
        ys.push_back(y);
    ys.push_back(speed.back());
    const double lo = speed.front(), span = speed.back() - speed.front();
    const double buckets = static_cast<double>(speed.size());
    for (int b = 0; b <= 4000; ++b) {  // near the bucket edges (when the index has n buckets)
      const double edge = lo + span * (static_cast<double>(b) / 4000.0);
      const double at = lo + static_cast<double>(b % static_cast<int>(buckets)) * span / buckets;
      for (double y : {edge, at, std::nextafter(at, 0.0), std::nextafter(at, 10.0)})
        ys.push_back(y);
    }
    for (int k = 0; k < 20000; ++k) ys.push_back(lo + span * unit(rng));
    for (double y : ys) {
      const double want = reference_magnitude(p, law, y);
      ASSERT_EQ(std::bit_cast<std::uint64_t>(law.magnitude(y)), std::bit_cast<std::uint64_t>(want))
          << "rows " << speed.size() << ", y = " << y;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(law.magnitude(-y)),
                std::bit_cast<std::uint64_t>(want));
      ++compared;
    }
  }
  EXPECT_GT(compared, 500000u);
}

TEST(TableLaw, RefusesEventsWhenItsFirstValueIsNotBelowTheThreshold) {
  EXPECT_NO_THROW(check_law_drives_events(sample_params()));
  EXPECT_THROW(check_law_drives_events(table_params({0.1, 1}, {1.0, 0.5})), Error);
}

TEST(TableLaw, ThetaRefusesIt) {
  const auto theta = make_stepper("theta", 1);
  try {
    check_time_step(*theta, sample_params(), 0.01);
    FAIL() << "theta accepted the table law";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("friction.law = table"), std::string::npos) << e.what();
  }
}

// The thesis law sampled finely up to y = 2 drives the same single-block stick-slip as
// the law itself: its accelerations agree to the interpolation error (h^2/8 max|phi''|).
TEST(TableLaw, ATabulatedThesisLawIsTheThesisLaw) {
  ModelParams thesis = table_params({}, {});
  thesis.law = law_id<law::Thesis>;
  const law::Thesis exact(thesis);
  FrictionTable t;
  for (int i = 0; i <= 2000; ++i) {
    t.speed.push_back(i * 0.001);
    t.friction.push_back(exact.magnitude(i * 0.001));
  }
  ModelParams tabulated = thesis;
  tabulated.law = law_id<law::Table>;
  tabulated.table = t;
  const law::Table table(tabulated);
  const double s = 1 / ((1 - thesis.sigma) * thesis.v_c);
  const double bound = 0.001 * 0.001 / 8 * 2 * exact.kinetic0 * s * s;
  for (double y = 1e-4; y < 4; y *= 1.07)
    EXPECT_NEAR(table.magnitude(y), exact.magnitude(y), bound) << y;
}

// A run on a table of the thesis law (rows every 0.001 up to 2, the law itself beyond)
// against the same run on the thesis law: a 1DOF block in stick-slip, continuous drive.
// The laws differ by the interpolation error (< 7e-6 here); the mean and amplitude of the
// friction agree to 1e-3 relative.
double summary_number(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\"");
  if (at == std::string::npos) return std::nan("");
  return std::strtod(json.c_str() + json.find(':', at) + 1, nullptr);
}

TEST(TableLaw, ARunOnATabulatedThesisLawIsTheThesisLawsRun) {
  test::TempDir dir;
  const std::vector<std::string> common = {
      "--set", "model.kind=1dof",  "--set", "drive.mode=continuous",
      "--set", "run.duration=300", "--set", "drive.speed=0.05"};
  Scene scene;
  for (std::size_t i = 0; i + 1 < common.size(); i += 2) scene.apply_override(common[i + 1]);
  scene.apply_override("friction.law=thesis");
  const ModelParams p = model_from_scene(scene);
  const law::Thesis exact(p);
  FrictionTable t;
  for (int i = 0; i <= 2000; ++i) {
    t.speed.push_back(i * 0.001);
    t.friction.push_back(exact.magnitude(i * 0.001));
  }
  const std::string table = dir.write("thesis.csv", friction_table_csv(t));
  auto run = [&](const std::vector<std::string>& law, const std::string& out) {
    std::vector<std::string> args = {"run"};
    args.insert(args.end(), common.begin(), common.end());
    args.insert(args.end(), law.begin(), law.end());
    args.insert(args.end(), {"--out", dir.file(out)});
    const auto r = test::run_bkquake(args);
    EXPECT_EQ(r.status, 0) << r.err;
    return test::read_file(dir.file(out + "/summary.json"));
  };
  const std::string a = run({"--set", "friction.law=thesis"}, "thesis");
  const std::string b =
      run({"--set", "friction.law=table", "--set", "friction.table=" + table}, "table");
  for (const char* key : {"pad_friction_mean", "pad_friction_amplitude"}) {
    const double x = summary_number(a, key), y = summary_number(b, key);
    ASSERT_TRUE(std::isfinite(x)) << key << "\n" << a;
    EXPECT_NEAR(y, x, 1e-3 * std::abs(x)) << key;
  }
}

std::string write_table(const test::TempDir& dir, const std::string& name,
                        const std::string& text) {
  return dir.write(name, text);
}

TEST(FrictionTableFile, ReadsCommentsHeaderAndRows) {
  test::TempDir dir;
  const std::string f = write_table(dir, "law.csv",
                                    "# bkquake special-law\n# from 5 runs\n"
                                    "speed,friction,friction_err\n"
                                    "0.005,0.93,0.01\n\n0.01,0.91,0.01\n1,0.5,0\n");
  const FrictionTable t = read_friction_table(f);
  EXPECT_EQ(t.speed, (std::vector<double>{0.005, 0.01, 1}));
  EXPECT_EQ(t.friction, (std::vector<double>{0.93, 0.91, 0.5}));
  // Written back and read again: the same numbers.
  const std::string g = write_table(dir, "again.csv", friction_table_csv(t, {"copy"}));
  const FrictionTable u = read_friction_table(g);
  EXPECT_EQ(u.speed, t.speed);
  EXPECT_EQ(u.friction, t.friction);
  EXPECT_EQ(file_checksum(f).size(), 16u);
  EXPECT_NE(file_checksum(f), file_checksum(g));
}

TEST(FrictionTableFile, BadFilesNameTheFileTheLineAndWhatIsWrong) {
  test::TempDir dir;
  struct Case {
    const char* text;
    const char* expected;  // regex on the message
  };
  const Case cases[] = {
      {"", "no header line"},
      {"# only a comment\n", "no header line"},
      {"speed,mu\n0.1,0.5\n", "line 1: missing column 'friction'"},
      {"speed,friction\n", "no rows after the header"},
      {"speed,friction\n0.1,abc\n", "line 2: column 'friction': expected a number, got 'abc'"},
      {"speed,friction\n0.1,0.5,7\n", "line 2: expected 2 fields, got 3"},
      {"speed,friction\n0.2,0.5\n0.1,0.4\n", "line 3: speed 0.1 is not above"},
      {"speed,friction\n0.2,0.5\n0.2,0.4\n", "line 3: speed 0.2 is not above"},
      {"speed,friction\n-0.1,0.5\n", "line 2: speed must be finite and >= 0"},
      {"#x\nspeed,friction\n0.1,-0.5\n", "line 3: friction must be finite and >= 0"},
      {"speed,friction\n0.1,inf\n", "line 2: friction must be finite"},
  };
  for (const Case& c : cases) {
    const std::string f = write_table(dir, "bad.csv", c.text);
    try {
      read_friction_table(f);
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const Error& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(f, 0), 0u) << msg;
      EXPECT_TRUE(std::regex_search(msg, std::regex(c.expected))) << msg << " vs " << c.expected;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
  }
  EXPECT_THROW(read_friction_table(dir.file("missing.csv")), Error);
}

TEST(FrictionTableScene, ARelativePathIsTakenFromTheSceneFilesFolder) {
  test::TempDir dir;
  std::filesystem::create_directories(dir.path() / "scenes");
  write_table(dir, "scenes/law.csv", "speed,friction\n0.1,0.5\n1,0.4\n");
  const std::string scene_file =
      dir.write("scenes/s.ini", "[model]\nkind = 1dof\n[friction]\nlaw = table\ntable = law.csv\n");
  const Scene scene = Scene::from_file(scene_file);
  EXPECT_EQ(scene.text("friction.table"), (dir.path() / "scenes" / "law.csv").string());
  const ModelParams p = model_from_scene(scene);
  EXPECT_EQ(p.law, law_id<law::Table>);
  EXPECT_EQ(p.table.speed, (std::vector<double>{0.1, 1}));
  // The effective scene names the absolute path and reads back to the same scene.
  const std::string ini = scene.to_ini();
  EXPECT_NE(ini.find("table = " + scene.text("friction.table")), std::string::npos);
  EXPECT_EQ(Scene::from_text(ini, "effective"), scene);
  // The table key means nothing under another law.
  EXPECT_THROW(Scene::from_text("[friction]\nlaw = thesis\ntable = x.csv\n", "t").validate(),
               Error);
  EXPECT_THROW(Scene::from_text("[friction]\nlaw = table\n", "t").validate(), Error);
}

// A run records the table's path and checksum; a bad table is one line and exit 2.
TEST(FrictionTableRun, RecordsTheTableAndRefusesABadOneWithExit2) {
  test::TempDir dir;
  const std::string table = write_table(dir, "law.csv", "speed,friction\n0.01,0.9\n1,0.6\n");
  const std::vector<std::string> base = {"run",
                                         "--set",
                                         "model.kind=1dof",
                                         "--set",
                                         "drive.mode=continuous",
                                         "--set",
                                         "run.duration=20",
                                         "--set",
                                         "friction.law=table",
                                         "--set",
                                         "friction.table=" + table};
  auto args = base;
  args.insert(args.end(), {"--out", dir.file("ok")});
  const auto ok = test::run_bkquake(args);
  ASSERT_EQ(ok.status, 0) << ok.err;
  const std::string ini = test::read_file(dir.file("ok/scene.ini"));
  EXPECT_NE(ini.find("table = " + table), std::string::npos) << ini;
  EXPECT_NE(ini.find("# friction table " + table + " fnv1a64 " + file_checksum(table)),
            std::string::npos)
      << ini;

  write_table(dir, "law.csv", "speed,friction\n0.01,0.9\n0.001,0.6\n");
  args = base;
  args.insert(args.end(), {"--out", dir.file("bad")});
  const auto bad = test::run_bkquake(args);
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find(table + " line 3: speed 0.001 is not above"), std::string::npos)
      << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

}  // namespace
}  // namespace bkq
