// The streaming magnitude histogram: bin anchoring, D and R, rates, exact merge (bit for
// bit equal to the histogram of the concatenated sample) and the CSV round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "core/error.hpp"
#include "io/histogram_csv.hpp"
#include "stats/histogram.hpp"

namespace bkq {
namespace {

TEST(MagnitudeHistogram, BinsAreAnchoredAtMultiplesOfTheWidth) {
  MagnitudeHistogram h(0.5);
  h.add(0.1);
  h.add(0.49);
  h.add(0.5);
  h.add(-0.1);
  h.add(2.2);
  EXPECT_EQ(h.first_bin(), -1);
  EXPECT_EQ(h.last_bin(), 4);
  EXPECT_EQ(h.count(-1), 1);
  EXPECT_EQ(h.count(0), 2);
  EXPECT_EQ(h.count(1), 1);
  EXPECT_EQ(h.count(2), 0);
  EXPECT_EQ(h.count(4), 1);
  EXPECT_EQ(h.R(0), 4);
  EXPECT_EQ(h.R(2), 1);
  EXPECT_DOUBLE_EQ(h.D(0), 4.0);  // 2 events / 0.5
  EXPECT_EQ(h.events(), 5);
  EXPECT_DOUBLE_EQ(h.min_mu(), -0.1);
  EXPECT_DOUBLE_EQ(h.max_mu(), 2.2);
  EXPECT_NEAR(h.mean_mu(), (0.1 + 0.49 + 0.5 - 0.1 + 2.2) / 5, 1e-12);
}

TEST(MagnitudeHistogram, CsvHasTheContractColumnsAndRates) {
  MagnitudeHistogram h(0.2);
  h.add(1.05);
  h.add(1.1);
  h.add(1.5);
  h.set_loading(2.0, 10);
  const std::string text = histogram_csv(h);
  EXPECT_EQ(text.substr(0, text.find('\n')), "mu_low,mu_high,count,D,R,D_rate,R_rate");
  EXPECT_NE(text.find("\n1,1.2,2,10,3,0.5,0.15\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\n1.2,1.4,0,0,1,0,0.05\n"), std::string::npos) << text;
}

TEST(MagnitudeHistogram, MergeEqualsConcatenationBitForBit) {
  std::mt19937_64 rng(42);
  std::vector<double> mu(30000);
  for (auto& m : mu) m = -std::log1p(-static_cast<double>(rng() >> 11) * 0x1.0p-53) - 1.3;
  MagnitudeHistogram all(0.2), a(0.2), b(0.2), c(0.2);
  for (std::size_t i = 0; i < mu.size(); ++i) {
    all.add(mu[i]);
    (i < 7000 ? a : i < 19000 ? b : c).add(mu[i]);
  }
  a.set_loading(1.5, 100);
  b.set_loading(2.5, 100);
  c.set_loading(3.0, 100);
  all.set_loading(7.0, 100);
  MagnitudeHistogram m(0.2);
  m.merge(c);
  m.merge(a);
  m.merge(b);
  EXPECT_TRUE(m == all);
  EXPECT_EQ(histogram_csv(m), histogram_csv(all));
  EXPECT_EQ(m.sum_mu(), all.sum_mu());
  EXPECT_EQ(m.sum_mu2(), all.sum_mu2());
}

TEST(MagnitudeHistogram, MergeRefusesDifferentBinWidths) {
  MagnitudeHistogram a(0.2), b(0.1);
  b.add(1.0);
  EXPECT_THROW(a.merge(b), Error);
}

TEST(MagnitudeHistogram, CsvRoundTrip) {
  std::mt19937_64 rng(3);
  MagnitudeHistogram h(0.2);
  for (int i = 0; i < 5000; ++i) h.add(static_cast<double>(rng() % 10000) / 1000.0 - 2.0);
  h.set_loading(12.5, 50);
  const auto path = std::filesystem::temp_directory_path() / "bkq_test_stats_hist.csv";
  write_histogram_csv(h, path);
  const MagnitudeHistogram r = read_histogram_csv(path, 12.5, 50, 0.2);
  std::filesystem::remove(path);
  EXPECT_EQ(histogram_csv(r), histogram_csv(h));
  EXPECT_EQ(r.events(), h.events());
  EXPECT_EQ(r.first_bin(), h.first_bin());
  EXPECT_FALSE(r.exact_moments());
}

TEST(MagnitudeHistogram, RejectsNonFiniteMagnitudes) {
  MagnitudeHistogram h;
  EXPECT_THROW(h.add(std::nan("")), Error);
  EXPECT_THROW(h.add(HUGE_VAL), Error);
}

}  // namespace
}  // namespace bkq
