// Spectra (thesis §4.3) and the special speed (eq. 4.8): two sines are found within one
// bin at their amplitudes; the spectrum command refuses a run of the wrong mode; a chain
// released from the threshold under constant kinetic friction is back at rest after half
// a period, pi sqrt(m_u/k_p); the special law is read from BK runs' segments.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "app/special_law.hpp"
#include "app/special_speed.hpp"
#include "app/spectrum.hpp"
#include "core/error.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"
#include "stats/spectrum.hpp"

namespace bkq {
namespace {

TEST(Spectrum, FindsTwoSinesWithinOneBin) {
  const double dt = 0.1, f1 = 0.2249, f2 = 1.37, a1 = 0.8, a2 = 0.3;
  std::vector<double> x;
  for (int i = 0; i < 7001; ++i) {  // 7001 is prime: the series is cut to a smooth length
    const double t = i * dt;
    x.push_back(5.0 + a1 * std::sin(2 * std::numbers::pi * f1 * t) +
                a2 * std::cos(2 * std::numbers::pi * f2 * t + 1.0));
  }
  for (Window w : {Window::Hann, Window::Rectangular}) {
    const Spectrum s = amplitude_spectrum(x, dt, w);
    EXPECT_LE(s.used, x.size());
    EXPECT_GE(s.used, 6900u);
    EXPECT_NEAR(s.resolution, 1.0 / (s.used * dt), 1e-15);
    const auto peaks = strongest_peaks(s, 2);
    ASSERT_EQ(peaks.size(), 2u);
    EXPECT_NEAR(peaks[0].frequency, f1, s.resolution);
    EXPECT_NEAR(peaks[1].frequency, f2, s.resolution);
    // Off-bin sines lose some height to the window (scalloping): at most 36 % for the
    // rectangular window, 15 % for Hann.
    EXPECT_NEAR(peaks[0].amplitude, a1, 0.36 * a1);
    EXPECT_NEAR(peaks[1].amplitude, a2, 0.36 * a2);
    // The mean is removed: nothing at f = 0 without a window (Hann leaks a little there).
    if (w == Window::Rectangular) {
      EXPECT_LT(s.amplitude[0], 1e-9);
    }
    EXPECT_LT(s.amplitude[0], 0.01);
  }
}

TEST(Spectrum, SineOnABinReadsItsAmplitude) {
  const double dt = 0.5;
  const int n = 1024;
  std::vector<double> x;
  for (int i = 0; i < n; ++i) x.push_back(2.5 * std::sin(2 * std::numbers::pi * 64 * i / n));
  const Spectrum s = amplitude_spectrum(x, dt, Window::Hann);
  EXPECT_NEAR(s.amplitude[64], 2.5, 1e-9);
  EXPECT_NEAR(s.frequency[64], 64.0 / (n * dt), 1e-12);
}

TEST(Spectrum, NaturalFrequenciesOfTable31) {
  Scene scene = Scene::from_file(BKQUAKE_SOURCE_DIR "/data/scenes/thesis.ini");
  const NaturalFrequencies f = natural_frequencies(model_from_scene(scene));
  // sqrt(200/100)/(2 pi) and that times sqrt(1 - 1/144); block sqrt(201)/(2 pi).
  EXPECT_NEAR(f.pad, std::sqrt(2.0) / (2 * std::numbers::pi), 1e-12);
  EXPECT_NEAR(f.pad_damped, f.pad * std::sqrt(1 - 1.0 / 144), 1e-9);
  EXPECT_NEAR(f.block, 2.256, 1e-3);
}

TEST(Spectrum, CommandRefusesAnEventRunAndWritesSpectrumCsv) {
  test::TempDir dir;
  const std::string events = dir.file("events");
  auto r = test::run_bkquake(
      {"run", "--set", "run.events=20", "--set", "run.transient_events=0", "--out", events});
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::run_bkquake({"spectrum", events});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("event-driven run"), std::string::npos) << r.err;

  const std::string cont = dir.file("cont");
  r = test::run_bkquake({"run", BKQUAKE_SOURCE_DIR "/data/scenes/thesis.ini", "--set",
                         "model.blocks=10", "--set", "run.duration=200", "--set",
                         "drive.step_interval=100", "--out", cont});
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::run_bkquake({"spectrum", cont, "--segment", "1", "--signal", "pad_velocity"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("strongest peaks"), std::string::npos);
  // The linear modes at the segment's speed are printed beside the peaks.
  EXPECT_NE(r.out.find("linear modes of steady sliding at v = "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("chain  0"), std::string::npos) << r.out;
  const std::string csv = test::read_file(cont + "/spectrum.csv");
  EXPECT_NE(csv.find("# window hann, mean removed, resolution"), std::string::npos);
  EXPECT_NE(csv.find("\nfrequency,amplitude\n"), std::string::npos);
  r = test::run_bkquake({"spectrum", cont, "--segment", "2"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--segment = 2"), std::string::npos) << r.err;
}

ModelParams thesis_params(const std::vector<std::pair<std::string, std::string>>& keys) {
  Scene scene = Scene::from_file(BKQUAKE_SOURCE_DIR "/data/scenes/thesis.ini");
  for (const auto& [k, v] : keys) scene.set(k, v);
  return model_from_scene(scene);
}

TEST(SpecialSpeed, ConstantKineticFrictionGivesHalfAPeriod) {
  // A flat law (v_c huge) at 70 % of F0, on blocks of mass 2 and springs 0.5.
  const ModelParams p = thesis_params({{"friction.vc", "1e12"},
                                       {"friction.sigma", "0.3"},
                                       {"model.s_m", "2"},
                                       {"model.s_p", "0.5"},
                                       {"model.blocks", "10"}});
  const SpecialSpeed s = special_speed(p);
  const double expected = std::numbers::pi * std::sqrt(p.m_u / p.k_p);
  EXPECT_NEAR(s.t_death, expected, 1e-6 * expected);
  EXPECT_NEAR(s.v_special, p.F0 * p.m_u / (p.k_p * s.t_death), 1e-12);
}

TEST(SpecialSpeed, ThesisLawTakesLongerThanHalfAPeriod) {
  // Velocity weakening lowers the friction while the block moves, so the swing runs past
  // the constant-friction half period; the thesis reports 3.589 for Table 3.1.
  const SpecialSpeed s = special_speed(thesis_params({}));
  EXPECT_GT(s.t_death, std::numbers::pi);
  EXPECT_NEAR(s.t_death, 3.589, 0.01);
}

TEST(SpecialLaw, RefusesARunThatIsNotBk) {
  test::TempDir dir;
  const std::string cont = dir.file("bkp");
  auto r = test::run_bkquake({"run", BKQUAKE_SOURCE_DIR "/data/scenes/thesis.ini", "--set",
                              "model.blocks=10", "--set", "run.duration=200", "--set",
                              "drive.step_interval=100", "--out", cont});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THROW(special_law({cont}), Error);
  const std::string bk = dir.file("bk");
  r = test::run_bkquake({"run", BKQUAKE_SOURCE_DIR "/data/scenes/thesis.ini", "--set",
                         "model.kind=bk", "--set", "model.blocks=10", "--set", "run.duration=200",
                         "--set", "drive.step_interval=100", "--out", bk});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto law = special_law({bk});
  ASSERT_EQ(law.size(), 2u);
  EXPECT_NEAR(law[0].speed, 0.005, 1e-12);
  EXPECT_NEAR(law[1].speed, 0.010, 1e-12);
  // Held pad, stick-slip: the mean friction per unit block mass lies below F0 and above 0.
  for (const auto& p : law) {
    EXPECT_GT(p.friction, 0.0);
    EXPECT_LT(p.friction, 1.0);
  }
}

}  // namespace
}  // namespace bkq
