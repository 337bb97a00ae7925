// The plot scripts, run with Debian's /usr/bin/python3 as users do:
// plot_gr.py draws the fitted law so that it passes through the data in the window (R at
// both window edges exactly: the window's law plus the events above it; D's expected
// counts adding up to the window's events) and writes its PNG; every script answers a
// folder of the wrong kind with one line and exit 2, not a traceback.
// plot_sweep.py draws total errors, the refit of sweep_fit.csv and published values, with
// legends that cover no data.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "io/folder_lock.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;

const std::string kPython = "/usr/bin/python3";

std::string script(const std::string& name) {
  return std::string(BKQUAKE_SOURCE_DIR) + "/analysis/" + name;
}

void expect_one_line_refusal(const test::ProcessResult& r, const std::string& fragment) {
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("Traceback"), std::string::npos) << r.err;
}

class Plots : public ::testing::Test {
 protected:
  void SetUp() override {
    if (test::run_process(kPython, {"-c", "import numpy, matplotlib"}).status != 0)
      GTEST_SKIP() << "no numpy/matplotlib for /usr/bin/python3";
  }
  test::TempDir dir_;
};

TEST_F(Plots, GrFitLinePassesThroughTheDataInTheWindow) {
  const std::string run = dir_.file("run");
  const auto r = test::run_bkquake({"run", "--set", "model.blocks=50", "--set", "run.events=20000",
                                    "--set", "run.transient_events=500", "--out", run, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string png = dir_.file("gr.png");
  const auto p = test::run_process(kPython, {script("plot_gr.py"), run, "--out", png});
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_GT(fs::file_size(png), 10000u);
  // The law drawn on R(mu) meets R at the window's edges; D's expected counts sum to the
  // window's events.
  const std::string check =
      "import sys; sys.path.insert(0, '" + script("") +
      "')\n"
      "import numpy as np, bkquake_io, plot_gr\n"
      "h = bkquake_io.load_histogram(sys.argv[1]); s = bkquake_io.load_summary(sys.argv[1])\n"
      "b, lo, hi = bkquake_io.fit_window(s)\n"
      "edges, centres, d_fit, r_fit = plot_gr.fitted_law(h, b, lo, hi)\n"
      "R = lambda mu: h['count'][h['mu_low'] >= mu - 1e-9].sum()\n"
      "w = h['mu_high'][0] - h['mu_low'][0]\n"
      "n_win = R(lo) - R(hi)\n"
      "assert abs(r_fit[0] - R(lo)) < 1e-6 * R(lo), (r_fit[0], R(lo))\n"
      "assert abs(r_fit[-1] - R(hi)) < 1e-6 * R(lo), (r_fit[-1], R(hi))\n"
      "assert abs(d_fit.sum() * w - n_win) < 1e-6 * n_win, (d_fit.sum() * w, n_win)\n"
      "assert np.all(np.diff(r_fit) < 0) and b > 0\n";
  const auto c = test::run_process(kPython, {"-c", check, run});
  EXPECT_EQ(c.status, 0) << c.err;
}

// plot_gr.py --mu-min/--mu-max refits in Python what `bkquake fit` fits on the same window:
// b and its systematic error agree to rounding; plot_b_scan.py draws b_scan.csv and refuses
// a file of another kind in one line.
TEST_F(Plots, GrRefitAndBScanMatchBkquakeFit) {
  const std::string run = dir_.file("run");
  ASSERT_EQ(test::run_bkquake({"run", "--set", "run.events=20000", "--set",
                               "run.transient_events=500", "--out", run, "--quiet"})
                .status,
            0);
  const std::string json = dir_.file("fit.json");
  ASSERT_EQ(test::run_bkquake({"fit", run + "/histogram.csv", "--mu-min", "-7.6", "--mu-max", "-2",
                               "--json", json, "--scan", "--out", dir_.file("scan")})
                .status,
            0);
  const std::string check =
      "import sys, json; sys.path.insert(0, '" + script("") +
      "')\n"
      "import bkquake_io, plot_gr\n"
      "h = bkquake_io.load_histogram(sys.argv[1]); f = json.load(open(sys.argv[2]))['fit']\n"
      "b, err = plot_gr.binned_mle(h, -7.6, -2.0)\n"
      "assert abs(b - f['b_mle']) < 1e-6 * b, (b, f['b_mle'])\n"
      "assert abs(err - f['b_mle_err']) < 1e-4 * err, (err, f['b_mle_err'])\n"
      "s = plot_gr.systematic(h, -7.6, -2.0)\n"
      "assert abs(s - f['b_mle_sys_err']) < 1e-6, (s, f['b_mle_sys_err'])\n";
  const auto c = test::run_process(kPython, {"-c", check, run, json});
  EXPECT_EQ(c.status, 0) << c.err;
  const std::string png = dir_.file("gr.png");
  const auto p = test::run_process(
      kPython, {script("plot_gr.py"), run, "--mu-min", "-7.6", "--mu-max", "-2", "--out", png});
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_GT(fs::file_size(png), 10000u);
  const std::string scan_png = dir_.file("scan.png");
  const auto q =
      test::run_process(kPython, {script("plot_b_scan.py"), dir_.file("scan"), "--out", scan_png});
  ASSERT_EQ(q.status, 0) << q.err;
  EXPECT_GT(fs::file_size(scan_png), 10000u);
  expect_one_line_refusal(
      test::run_process(kPython, {script("plot_b_scan.py"), run + "/histogram.csv"}),
      "expected the columns");
}

TEST_F(Plots, AFolderOfTheWrongKindIsOneLine) {
  // A continuous run's folder as it was before it had a histogram: no histogram.csv.
  const std::string cont = dir_.file("continuous");
  fs::create_directories(cont);
  dir_.write("continuous/summary.json", "{\"mode\": \"continuous\"}\n");
  dir_.write("continuous/timeseries.csv", "t,load\n0,0\n");
  expect_one_line_refusal(test::run_process(kPython, {script("plot_gr.py"), cont}),
                          "has no histogram.csv");
  expect_one_line_refusal(test::run_process(kPython, {script("plot_work_precision.py"), cont}),
                          "has no accuracy.csv");
  expect_one_line_refusal(
      test::run_process(kPython, {script("plot_work_precision.py"), cont + "/timeseries.csv"}),
      "missing columns");
  // An interrupted run has no histogram yet (it is written at the end): the line says why.
  const std::string stopped = dir_.file("stopped");
  fs::create_directories(stopped);
  dir_.write("stopped/summary.json", "{\"mode\": \"events\", \"status\": \"interrupted\"}\n");
  expect_one_line_refusal(test::run_process(kPython, {script("plot_gr.py"), stopped}),
                          "(an interrupted events run: bkquake run ... --resume finishes it) has "
                          "no histogram.csv");
  expect_one_line_refusal(test::run_process(kPython, {script("compare_modes.py"), "--events-run",
                                                      cont, "--out-dir", dir_.file("modes")}),
                          "has no catalog.csv");
}

// The folder rule of derived outputs holds for the plots: by default a figure goes into the
// folder it was drawn from (plot_stability.py wrote into the working folder), under that
// folder's lock (a live holder refuses, a stale lock of this host is taken over, none is left
// behind), and never over an input or a run's own file.
TEST_F(Plots, FiguresGoIntoTheFolderReadUnderItsLockAndNeverOverAnInput) {
  const std::string st = dir_.file("st");
  ASSERT_EQ(test::run_bkquake({"stability", "--set", "drive.mode=continuous", "--set",
                               "model.blocks=5", "--sweep", "drive.speed=0.05:0.2:3", "--out", st})
                .status,
            0);
  const std::string cwd = dir_.file("cwd");
  fs::create_directories(cwd);
  auto p = test::run_process(kPython, {script("plot_stability.py"), "sweep", st}, cwd);
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_TRUE(fs::exists(st + "/stability_sweep.png"));
  p = test::run_process(kPython, {script("plot_stability.py"), "eigen", st}, cwd);
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_TRUE(fs::exists(st + "/stability_eigen.png"));
  EXPECT_TRUE(fs::is_empty(cwd)) << "a plot wrote into the working folder";
  EXPECT_FALSE(fs::exists(st + "/bkquake.lock"));

  const std::string run = dir_.file("run");
  ASSERT_EQ(test::run_bkquake({"run", "--set", "run.events=3000", "--set",
                               "run.transient_events=100", "--out", run, "--quiet"})
                .status,
            0);
  const std::string histogram = test::read_file(run + "/histogram.csv");
  expect_one_line_refusal(
      test::run_process(kPython, {script("plot_gr.py"), run, "--out", run + "/histogram.csv"}),
      "is not an image file name");
  expect_one_line_refusal(
      test::run_process(kPython, {script("plot_stability.py"), "sweep", st, "--out", st}),
      "is not an image file name");
  EXPECT_EQ(test::read_file(run + "/histogram.csv"), histogram);
  {
    const FolderLock held(run, "test", StaleLock::Refuse);
    expect_one_line_refusal(test::run_process(kPython, {script("plot_gr.py"), run}),
                            "is in use by bkquake test");
    EXPECT_FALSE(fs::exists(run + "/gr.png"));
  }
  char host[256] = {};
  ASSERT_EQ(::gethostname(host, sizeof host - 1), 0);
  // A lock left by a killed process: its flock went with it.
  dir_.write("run/bkquake.lock", std::string("bkquake folder lock\nhost ") + host +
                                     "\npid 999999999\ncommand run\nsince 2026-01-01T00:00:00Z\n");
  p = test::run_process(kPython, {script("plot_gr.py"), run});
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_NE(p.err.find("taking over the stale lock"), std::string::npos) << p.err;
  EXPECT_TRUE(fs::exists(run + "/gr.png"));
  EXPECT_FALSE(fs::exists(run + "/bkquake.lock"));
}

// plot_lattice.py draws a lattice run (the OFC automaton on 24 x 16 sites, with slip maps)
// into RUN_DIR/lattice.png; the maps it draws are the largest events of the catalogue with
// mu >= 2, each site's value where the event's sites are (as many as the catalogue's
// blocks, inside its box) and summing to its moment; a chain's run and a single row (no
// row columns) are refused in one line.
TEST_F(Plots, LatticeFigureOfAnOfcRunAndRefusalsOfAChain) {
  const auto ofc = [](const std::string& rows, const std::string& out) {
    return test::run_bkquake({"run", "--set", "model.kind=ofc", "--set", "model.blocks=24", "--set",
                              "model.rows=" + rows, "--set", "ofc.alpha=0.2", "--set",
                              "run.events=3000", "--set", "output.event_slip=2", "--quiet", "--out",
                              out});
  };
  const std::string run = dir_.file("ofc");
  ASSERT_EQ(ofc("16", run).status, 0);
  const auto p = test::run_process(kPython, {script("plot_lattice.py"), run, "--largest", "5"});
  ASSERT_EQ(p.status, 0) << p.err;
  const std::string png = test::read_file(run + "/lattice.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  const std::string check =
      "import sys; sys.path.insert(0, '" + script("") +
      "')\n"
      "import numpy as np, bkquake_io, plot_lattice\n"
      "cat = bkquake_io.load_catalog(sys.argv[1])\n"
      "maps = plot_lattice.largest_maps(plot_lattice.load_slip_maps(sys.argv[1]), 24, 16, 3)\n"
      "mu = np.asarray(cat['magnitude'], float)\n"
      "top = np.sort(mu)[::-1][:3]\n"
      "got = [np.log(np.nansum(m[1])) for m in maps]\n"
      "assert len(maps) == 3 and np.allclose(got, top, rtol=0, atol=1e-12), (got, top)\n"
      "for e, released, topplings in maps:\n"
      "    i = int(np.flatnonzero(np.asarray(cat['event']) == e)[0])\n"
      "    y, x = np.nonzero(~np.isnan(released))\n"
      "    assert len(x) == int(cat['blocks'][i]) and topplings.sum() == int(cat['topplings'][i])\n"
      "    assert x.min() == cat['first_block'][i] and x.max() == cat['last_block'][i]\n"
      "    assert y.min() == cat['first_row'][i] and y.max() == cat['last_row'][i]\n"
      "    assert abs(np.nansum(released) - cat['moment'][i]) < 1e-9 * cat['moment'][i]\n"
      "print('maps', len(maps))\n";
  const auto c = test::run_process(kPython, {"-c", check, run});
  ASSERT_EQ(c.status, 0) << c.err;
  EXPECT_NE(c.out.find("maps 3"), std::string::npos) << c.out;
  const std::string chain = dir_.file("chain");
  ASSERT_EQ(test::run_bkquake({"run", "--set", "run.events=200", "--quiet", "--out", chain}).status,
            0);
  expect_one_line_refusal(test::run_process(kPython, {script("plot_lattice.py"), chain}),
                          "has no trigger_row, first_row, last_row");
  const std::string row = dir_.file("row");
  ASSERT_EQ(ofc("1", row).status, 0);
  expect_one_line_refusal(test::run_process(kPython, {script("plot_lattice.py"), row}),
                          "not a lattice");
  EXPECT_FALSE(fs::exists(row + "/lattice.png"));
}

// The width in pixels of a PNG file's image (its IHDR chunk, big-endian at bytes 16..19).
std::uint32_t png_width(const std::string& png) {
  if (png.size() < 24) return 0;
  std::uint32_t w = 0;
  for (int i = 16; i < 20; ++i) w = (w << 8) | static_cast<unsigned char>(png[i]);
  return w;
}

// plot_lattice.py on the BK lattice: an event run gets the automaton's three panels; a
// continuous run that wrote blocks.csv gets a fourth, the stress field, which is checked
// against the run's own numbers on every row of blocks.csv: its sum is minus timeseries.csv's
// pad friction (the springs between blocks cancel in the sum, on free and periodic edges),
// and where no block slides no block carries more than its threshold (one step's loading
// aside). Two lattices: 1/r^3 springs within r <= 2 with periodic rows (carlson-langer
// units), and a pad under nearest neighbours (thesis units).
TEST_F(Plots, LatticeFigureOfBkRunsAndTheStressFieldOfAContinuousRun) {
  const std::string events = dir_.file("bk");
  ASSERT_EQ(test::run_bkquake({"run", "--set", "model.blocks=12", "--set", "model.rows=10", "--set",
                               "run.events=400", "--quiet", "--out", events})
                .status,
            0);
  const auto p = test::run_process(kPython, {script("plot_lattice.py"), events, "--largest", "5"});
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_EQ(png_width(test::read_file(events + "/lattice.png")), 1650u);
  expect_one_line_refusal(test::run_process(kPython, {script("plot_lattice.py"), events, "--time",
                                                      "3", "--out", dir_.file("t.png")}),
                          "continuous BK runs only");

  const std::vector<std::vector<std::string>> lattices = {
      {"model.blocks=10", "model.rows=6", "model.coupling=power", "model.range=2",
       "model.boundary_y=periodic"},
      {"model.kind=bkp", "model.parameterisation=thesis", "model.blocks=8", "model.rows=6"}};
  const std::string check =
      "import sys; sys.path.insert(0, '" + script("") +
      "')\n"
      "import numpy as np, bkquake_io, plot_lattice as pl\n"
      "run = sys.argv[1]; scene = bkquake_io.load_scene(run)\n"
      "nx, ny = int(scene['model']['blocks']), int(scene['model']['rows'])\n"
      "ts = bkquake_io.read_csv_columns(run + '/timeseries.csv')\n"
      "rows = np.loadtxt(run + '/blocks.csv', delimiter=',', skiprows=1, ndmin=2)\n"
      "assert len(rows) == len(ts['t']) > 100, (len(rows), len(ts['t']))\n"
      "thr = pl.lattice_springs(scene, nx, ny)[1]\n"
      "stuck, top = 0, 0.0\n"
      "for r, t, pf, sl, x in zip(rows, ts['t'], ts['pad_friction'], ts['sliding'], "
      "ts['pad_x']):\n"
      "    assert r[0] == float(t), (r[0], t)\n"
      "    f = pl.stress_field(scene, nx, ny, r[1:nx * ny + 1], float(x))\n"
      "    assert abs(f.sum() * thr + float(pf)) <= 1e-9 * max(1.0, abs(float(pf))), (t, "
      "f.sum() * thr, pf)\n"
      "    if float(sl) == 0:\n"
      "        stuck += 1; top = max(top, f.max())\n"
      "        assert f.max() <= 1 + 1e-3, (t, f.max())\n"
      "assert stuck > 20 and top > 0.9, (stuck, top)\n";
  int i = 0;
  for (const auto& sets : lattices) {
    const std::string run = dir_.file("continuous" + std::to_string(i++));
    std::vector<std::string> args = {"run", "--quiet", "--out", run};
    for (const char* s :
         {"drive.mode=continuous", "drive.speed=0.01", "run.duration=300", "output.blocks=true"})
      args.insert(args.end(), {"--set", s});
    for (const std::string& s : sets) args.insert(args.end(), {"--set", s});
    ASSERT_EQ(test::run_bkquake(args).status, 0) << sets[0];
    const auto q = test::run_process(kPython, {script("plot_lattice.py"), run});
    ASSERT_EQ(q.status, 0) << q.err;
    EXPECT_EQ(png_width(test::read_file(run + "/lattice.png")), 2200u) << sets[0];
    const auto c = test::run_process(kPython, {"-c", check, run});
    EXPECT_EQ(c.status, 0) << sets[0] << ": " << c.err;
  }
}

TEST_F(Plots, WorkPrecisionOfTheReferenceStudy) {
  const std::string png = dir_.file("wp.png");
  const auto p = test::run_process(
      kPython,
      {script("plot_work_precision.py"),
       std::string(BKQUAKE_SOURCE_DIR) + "/data/reference/accuracy/thesis.csv", "--out", png});
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_GT(fs::file_size(png), 10000u);
}

// plot_coupling_fronts.py measures a rupture front from the blocks' velocities: on a
// synthetic event whose onset runs out from block 50 at 20 blocks per unit time and whose
// velocity rises linearly to 1 in 0.3 time units, it finds one front each way with that
// speed, the width speed x (time from the 0.1 threshold to half the peak) = 20 x 0.12 and
// the leading edge speed x (time from 0.1 to 0.2) = 20 x 0.03.
TEST_F(Plots, CouplingFrontsMeasureTheSpeedAndWidthOfASyntheticFront) {
  const std::string check =
      "import sys; sys.path.insert(0, '" + script("") +
      "')\n"
      "import numpy as np, plot_coupling_fronts as f\n"
      "t = np.arange(0, 30, 0.01); n = 200; c = 20.0; stuck = -0.01\n"
      "onset = 5 + np.abs(np.arange(n) - 50) / c\n"
      "s = t[:, None] - onset[None, :]\n"
      "v = np.where((s > 0) & (s < 4), np.minimum(s / 0.3, 1.0), 0.0) + stuck\n"
      "fr = f.fronts(t, v, stuck, 0.1)\n"
      "assert len(fr) == 2, fr\n"
      "assert sorted(x[1] for x in fr) == [-1, 1], fr\n"
      "for _, _, blocks, speed, width, edge in fr:\n"
      "    assert blocks in (51, 150), fr\n"
      "    assert abs(speed - c) < 0.01 * c, fr\n"
      "    assert abs(width - c * 0.12) < 0.05 * c * 0.12, fr\n"
      "    assert abs(edge - c * 0.03) < 0.05 * c * 0.03, fr\n";
  const auto p = test::run_process(kPython, {"-c", check});
  EXPECT_EQ(p.status, 0) << p.err;
}

// plot_sweep.py draws sweep_fit.csv's b where `bkquake fit SWEEP_DIR` wrote it, with error
// bars whose half-length is the total error sqrt(b_err^2 + b_sys_err^2) of that file (the
// drawn bars themselves are measured, and --dump writes the same numbers); the point that
// sweep.csv's own fit left without b but the refit gave one is drawn; the published values
// of --reference are drawn on their key's panel; and no legend's box contains a point or
// an error bar's end in display coordinates.
TEST_F(Plots, SweepDrawsTheRefitWithTotalErrorsAndPublishedValuesAndLegendsOffTheData) {
  const std::string ini = dir_.write(
      "sw.ini", "[sweep]\nscene = " + std::string(BKQUAKE_SOURCE_DIR) +
                    "/data/scenes/cl-l10-a2.5-n100.ini\ncombine = product\nreplicas = 1\n"
                    "[vary]\nfriction.alpha = 2.5, 3\nmodel.blocks = 30, 50\n"
                    "[set]\nrun.events = 3000\nrun.transient_events = 300\n");
  const std::string sw = dir_.file("sw");
  auto r = test::run_bkquake({"sweep", ini, "--out", sw});
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::run_bkquake({"fit", sw, "--mu-min", "-7.6", "--mu-max", "-2"});
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_TRUE(fs::exists(sw + "/sweep_fit.csv"));
  const std::string ref =
      std::string(BKQUAKE_SOURCE_DIR) + "/data/reference/carlson-langer-published.csv";
  const std::string png = dir_.file("sweep_b.png");
  const std::string dump = dir_.file("drawn.csv");
  const auto p = test::run_process(
      kPython, {script("plot_sweep.py"), sw, "--out", png, "--reference", ref, "--dump", dump});
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_NE(p.out.find("sweep_fit.csv"), std::string::npos) << p.out;
  EXPECT_GT(fs::file_size(png), 10000u);
  const std::string check =
      "import sys, csv, math; sys.path.insert(0, '" + script("") +
      "')\n"
      "import numpy as np, plot_sweep\n"
      "sw, ref, dump = sys.argv[1:4]\n"
      "fit = {r['point']: r for r in csv.DictReader(open(sw + '/sweep_fit.csv'))}\n"
      "tot = lambda r: math.hypot(float(r['b_err']), float(r['b_sys_err']))\n"
      "want = sorted((round(float(r['b']), 9), round(tot(r), 9)) for r in fit.values() if r['b'])\n"
      "assert len(want) == 4, want\n"
      "old = [r for r in csv.DictReader(open(sw + '/sweep.csv')) if r['b']]\n"
      "assert len(old) < 4 or any(abs(float(o['b']) - float(fit[o['point']]['b'])) > 1e-9 "
      "for o in old), 'the refit changes b'\n"
      "fig, drawn, source = plot_sweep.make_figure(sw, True, ref)\n"
      "assert source == 'sweep_fit.csv', source\n"
      "fig.canvas.draw(); rend = fig.canvas.get_renderer()\n"
      "n_ref = 0\n"
      "for ax in fig.axes:\n"
      "    got, pts = [], []\n"
      "    for c in ax.containers:\n"
      "        line, caps, bars = c.lines\n"
      "        x, y = line.get_data()\n"
      "        if line.get_marker() == 'D':\n"
      "            n_ref += len(x); assert np.allclose(np.asarray(y, float), 1.0), y\n"
      "        else:\n"
      "            for seg in bars[0].get_segments():\n"
      "                (x0, y0), (x1, y1) = seg\n"
      "                got.append((round((y0 + y1) / 2, 9), round(abs(y1 - y0) / 2, 9)))\n"
      "        xy = np.array([x, y], dtype=float).T\n"
      "        for a, b in zip(xy[:-1], xy[1:]):\n"
      "            if line.get_linestyle() != 'None':\n"
      "                pts.extend(a + (b - a) * t for t in np.linspace(0, 1, 41))\n"
      "        pts.extend(xy)\n"
      "        for seg in bars[0].get_segments() if bars else []:\n"
      "            pts.extend(tuple(q) for q in seg)\n"
      "    assert sorted(got) == want, (sorted(got), want)\n"
      "    leg = ax.get_legend(); assert leg is not None\n"
      "    box = leg.get_window_extent(rend)\n"
      "    disp = ax.transData.transform(np.array(pts, dtype=float))\n"
      "    inside = [q for q in disp if box.x0 <= q[0] <= box.x1 and box.y0 <= q[1] <= box.y1]\n"
      "    assert not inside, ('legend covers data', inside)\n"
      "assert n_ref == 2, n_ref\n"
      "rows = list(csv.DictReader(open(dump)))\n"
      "assert len(rows) == 8 and all(r['source'] == 'sweep_fit.csv' for r in rows)\n"
      "for r in rows: assert abs(float(r['total_err']) - tot(r)) < 1e-12, r\n";
  const auto c = test::run_process(kPython, {"-c", check, sw, ref, dump});
  EXPECT_EQ(c.status, 0) << c.out << c.err;
  // --sweep-csv draws sweep.csv's own fit instead.
  const auto q = test::run_process(
      kPython, {script("plot_sweep.py"), sw, "--out", dir_.file("own.png"), "--sweep-csv"});
  ASSERT_EQ(q.status, 0) << q.err;
  EXPECT_NE(q.out.find("b from sweep.csv"), std::string::npos) << q.out;
}

}  // namespace
}  // namespace bkq
