// The seismicity statistics (stats/seismicity/) on synthetic catalogues with known answers,
// fed event by event as `bkquake seismicity` feeds them: a Poisson process (waiting times
// exponential, COV 1), recurrence intervals drawn from a Weibull law of known shape,
// aftershocks drawn from an Omori-Utsu rate K/(t + c)^p over a background, a catalogue
// without aftershocks, and a Båth case with a known magnitude difference. Each recovered
// value must lie within two of its standard errors of the truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "stats/seismicity/log_bins.hpp"
#include "stats/seismicity/moments.hpp"
#include "stats/seismicity/seismicity.hpp"

namespace bkq::seis {
namespace {

constexpr int kBlocks = 10;

Quake small(double t, double mu) {
  Quake q;
  q.t = t;
  q.mu = mu;
  q.moment = std::exp(mu);
  q.first = q.last = q.trigger = 3;
  q.blocks = 1;
  return q;
}

Quake big(double t, double mu) {
  Quake q = small(t, mu);
  q.first = 0;
  q.last = kBlocks - 1;
  q.blocks = kBlocks;
  return q;
}

SeismicityOptions by_mu(double mu) {
  SeismicityOptions o;
  o.blocks = kBlocks;
  o.mainshock.blocks = kBlocks;
  o.mainshock.mu = mu;
  return o;
}

TEST(SeismicityStats, LogBinsHoldTheirEdges) {
  const LogBins b = time_bins(10);
  for (std::size_t i = 1; i + 1 < b.size(); ++i) {
    EXPECT_EQ(b.index(b.low(i)), i) << b.low(i);
    EXPECT_EQ(b.index(std::nextafter(b.high(i), 0.0)), i);
  }
  EXPECT_EQ(b.index(0.0), 0u);
  EXPECT_DOUBLE_EQ(b.covered(11, b.low(11)), 0.0);
  EXPECT_DOUBLE_EQ(b.covered(11, b.high(11)), 1.0);
}

TEST(SeismicityStats, PoissonWaitingTimesHaveCovOne) {
  std::mt19937_64 rng(11);
  std::exponential_distribution<double> wait(2.0);
  std::normal_distribution<double> mag(-2, 1);
  Seismicity s(by_mu(100));
  double t = 0;
  for (int i = 0; i < 20000; ++i) {
    t += wait(rng);
    s.add(small(t, mag(rng)));
  }
  s.finish();
  const Moments& m = s.interevent().all().moments;
  EXPECT_NEAR(m.mean(), 0.5, 2 * 0.5 / std::sqrt(20000.0));
  // The COV's error of an exponential law is about 1/sqrt(n) (delta method).
  EXPECT_NEAR(m.cov_err(), 1 / std::sqrt(20000.0), 0.3 / std::sqrt(20000.0));
  EXPECT_NEAR(m.cov(), 1.0, 2 * m.cov_err());
  // A periodic catalogue is not Poisson: COV 0.
  Moments periodic;
  for (int i = 0; i < 100; ++i) periodic.add(1.0);
  EXPECT_NEAR(periodic.cov(), 0.0, 1e-12);
}

TEST(SeismicityStats, WeibullRecurrenceShapeIsRecovered) {
  const double k = 3.0, lambda = 2.0;
  std::mt19937_64 rng(5);
  std::weibull_distribution<double> interval(k, lambda);
  std::exponential_distribution<double> filler(20.0);
  Seismicity s(by_mu(3));
  double t = 0;
  for (int i = 0; i < 3000; ++i) {
    const double next = t + interval(rng);
    for (double u = t + filler(rng); u < next; u += filler(rng)) s.add(small(u, -3));
    s.add(big(next, 5));
    t = next;
  }
  s.finish();
  const WeibullFit& w = s.weibull();
  ASSERT_TRUE(w.ok);
  EXPECT_GT(w.k.err, 0);
  EXPECT_LT(w.k.err, 0.1);
  EXPECT_NEAR(w.k.value, k, 2 * w.k.err);
  EXPECT_NEAR(w.lambda.value, lambda, 2 * w.lambda.err);
  EXPECT_EQ(s.recurrence().system().moments.n(), 2999);
  // Every block is inside each mainshock: each block's intervals are the system's.
  EXPECT_EQ(s.recurrence().per_block().moments.n(), 2999 * kBlocks);
  EXPECT_NEAR(s.block_weibull().k.value, w.k.value, 1e-6 * w.k.value);
  // A Weibull law of shape 3 has COV 0.3636.
  EXPECT_NEAR(s.recurrence().system().moments.cov(), 0.3636,
              2 * s.recurrence().system().moments.cov_err());
}

TEST(SeismicityStats, LognormalRecurrenceIsRecovered) {
  std::mt19937_64 rng(12);
  std::lognormal_distribution<double> interval(0.5, 0.4);
  Seismicity s(by_mu(3));
  Moments log_sample;  // the ungrouped maximum-likelihood estimates: mean and deviation of ln t
  double t = 0;
  for (int i = 0; i < 3000; ++i) {
    const double x = interval(rng);
    t += x;
    s.add(big(t, 5));
    if (i > 0) log_sample.add(std::log(x));
  }
  s.finish();
  ASSERT_TRUE(s.lognormal().ok);
  // Grouping in 50 bins a decade loses little: the binned fit is the sample's own ML estimate
  // to a quarter of its error.
  const double n = static_cast<double>(log_sample.n());
  EXPECT_NEAR(s.lognormal().m.value, log_sample.mean(), 0.25 * s.lognormal().m.err);
  EXPECT_NEAR(s.lognormal().s.value, std::sqrt(log_sample.variance() * (n - 1) / n),
              0.25 * s.lognormal().s.err);
  EXPECT_NEAR(s.lognormal().m.value, 0.5, 2 * s.lognormal().m.err);
  EXPECT_NEAR(s.lognormal().s.value, 0.4, 2 * s.lognormal().s.err);
}

// Mainshocks every T; in each window a background rate mu and aftershocks of rate
// K/(t + c)^p, drawn by inverting their cumulative rate.
void omori_catalogue(Seismicity& s, std::mt19937_64& rng, int sequences, double T, double mu,
                     double K, double c, double p) {
  std::uniform_real_distribution<double> u(0, 1);
  const double q = 1 - p, a = std::pow(c, q), b = std::pow(T + c, q);
  const double expected = K * (b - a) / q;
  std::vector<double> times;
  for (int k = 0; k < sequences; ++k) {
    const double t0 = k * T;
    s.add(big(t0, 6));
    times.clear();
    std::poisson_distribution<int> n_after(expected), n_back(mu * T);
    for (int i = n_after(rng); i > 0; --i)
      times.push_back(std::pow(a + u(rng) * (b - a), 1 / q) - c);
    for (int i = n_back(rng); i > 0; --i) times.push_back(u(rng) * T);
    std::sort(times.begin(), times.end());
    for (double t : times) s.add(small(t0 + t, -2));
  }
  s.add(big(sequences * T, 6));
}

TEST(SeismicityStats, OmoriUtsuPAndCAreRecovered) {
  std::mt19937_64 rng(3);
  Seismicity s(by_mu(3));
  const double K = 20, c = 0.05, p = 1.2, mu = 1.0;
  omori_catalogue(s, rng, 300, 100.0, mu, K, c, p);
  s.finish();
  const OmoriFit& f = s.aftershocks();
  ASSERT_TRUE(f.excess) << f.note;
  EXPECT_GT(f.lr, kOmoriLrThreshold);
  EXPECT_NEAR(f.t_max, 10.0, 0.1);  // a tenth of the windows of 100
  for (const auto& [name, got, truth] :
       {std::tuple{"p", f.p, p}, std::tuple{"c", f.c, c}, std::tuple{"K", f.K, K},
        std::tuple{"background", f.background, mu}}) {
    EXPECT_GT(got.err, 0) << name;
    EXPECT_NEAR(got.value, truth, 2 * got.err) << name;
  }
  EXPECT_LT(f.p.err, 0.05);
  // The events above the background in the fitted span: K int_0^10 (t + c)^-p dt per window.
  const double per_window = K * (std::pow(10 + c, 1 - p) - std::pow(c, 1 - p)) / (1 - p);
  EXPECT_NEAR(f.excess_events / (300 * per_window), 1.0, 0.05);
}

TEST(SeismicityStats, NoAftershockExcessIsSaidNotFitted) {
  std::mt19937_64 rng(4);
  Seismicity s(by_mu(3));
  omori_catalogue(s, rng, 300, 100.0, 1.0, 0.0, 0.05, 1.2);  // K = 0: background only
  s.finish();
  EXPECT_FALSE(s.aftershocks().excess);
  EXPECT_NE(s.aftershocks().note.find("no excess"), std::string::npos) << s.aftershocks().note;
  EXPECT_NEAR(s.aftershocks().background_only, 1.0, 0.05);
  EXPECT_FALSE(s.foreshocks().excess);
}

TEST(SeismicityStats, BathDifferenceIsTheKnownOne) {
  // Mainshocks of mu 6 (or 6.5) whose largest aftershock is 1.2 below them.
  Seismicity s(by_mu(5.5));
  double t = 0;
  for (int k = 0; k < 40; ++k) {
    const double main = k % 2 ? 6.5 : 6.0;
    s.add(big(t, main));
    s.add(small(t + 0.001, main - 1.2));
    for (int i = 1; i < 10; ++i) s.add(small(t + i, main - 3 - 0.1 * i));
    t += 20;
  }
  s.finish();
  EXPECT_EQ(s.bath().sequences, 40);
  EXPECT_NEAR(s.bath().delta_mu, 1.2, 1e-12);
  EXPECT_NEAR(s.bath().delta_mw(), 1.2 / (1.5 * std::log(10.0)), 1e-12);
  EXPECT_NEAR(s.bath().delta_mu_err, 0.0, 1e-9);
}

TEST(SeismicityStats, MomentRateKeepsEveryEventAndTheBudget) {
  // N blocks, each event slips one block by 1 after 1/N of load: budget exactly 1.
  SeismicityOptions o = by_mu(100);
  Seismicity s(o);
  const int n = 100000;
  for (int i = 0; i < n; ++i) s.add(small(static_cast<double>(i) / kBlocks, 0.0));
  s.finish();
  EXPECT_NEAR(s.moment_rate().budget(kBlocks), 1.0, 1e-12);
  double events = 0, moment = 0;
  for (std::size_t k = 0; k < s.moment_rate().moment().size(); ++k) {
    events += static_cast<double>(s.moment_rate().events()[k]);
    moment += s.moment_rate().moment()[k];
  }
  EXPECT_EQ(events, n);
  EXPECT_NEAR(moment, n, 1e-6);
  EXPECT_LE(s.moment_rate().moment().size(), MomentRate::kMaxBins);
  EXPECT_GE(s.moment_rate().moment().size(), MomentRate::kMaxBins / 2);
}

TEST(SeismicityStats, ScalingExponentOfAPowerLaw) {
  Seismicity s(by_mu(100));
  for (int i = 0; i < 1000; ++i) {
    const int len = 1 + i % kBlocks;
    Quake q = small(i, 0);
    q.first = 0;
    q.last = len - 1;
    q.moment = 0.3 * std::pow(len, 2.0);
    q.mu = std::log(q.moment);
    q.duration = 0.1 * len;
    s.add(q);
  }
  s.finish();
  EXPECT_NEAR(s.scaling().length().fit.slope(), 2.0, 1e-9);
  EXPECT_NEAR(s.scaling().duration().fit.slope(), 2.0, 1e-9);
  EXPECT_NEAR(s.scaling().length().binned_fit().slope(), 2.0, 1e-9);
  EXPECT_GE(s.scaling().length().binned_fit().n(), 5);
}

}  // namespace
}  // namespace bkq::seis

namespace bkq::seis {
namespace {

// Distances on a lattice: Euclidean in site spacings; along a periodic axis the shorter way
// round, so shifting both sites by the same amount (mod the axis) leaves every distance as
// it was; along a free axis a shift across the edge changes it.
TEST(SeismicityGeometry, LatticeDistancesAreEuclideanAndShiftInvariantWherePeriodic) {
  const Geometry torus{11, 7, true, true};
  EXPECT_EQ(torus.distance(0, 0, 4, 3), 5.0);
  EXPECT_EQ(torus.distance(0, 0, 3, 4), std::sqrt(18.0));  // 4 rows down is 3 rows up
  EXPECT_EQ(torus.distance(0, 0, 10, 6), std::sqrt(2.0));  // one step each way round
  EXPECT_EQ(torus.max_distance(), std::sqrt(5.0 * 5.0 + 3.0 * 3.0));
  for (int sx = 0; sx < 11; ++sx)
    for (int sy = 0; sy < 7; ++sy)
      for (int x1 = 0; x1 < 11; x1 += 3)
        for (int y2 = 0; y2 < 7; y2 += 2)
          ASSERT_EQ(torus.distance((x1 + sx) % 11, sy % 7, (5 + sx) % 11, (y2 + sy) % 7),
                    torus.distance(x1, 0, 5, y2))
              << sx << " " << sy << " " << x1 << " " << y2;
  const Geometry open{11, 7, false, false};
  EXPECT_EQ(open.distance(0, 0, 10, 6), std::sqrt(100.0 + 36.0));
  EXPECT_EQ(open.max_distance(), std::sqrt(100.0 + 36.0));
  // A cylinder: wrapped along strike only.
  const Geometry cylinder{11, 7, true, false};
  EXPECT_EQ(cylinder.distance(0, 0, 10, 6), std::sqrt(1.0 + 36.0));
  // A chain keeps |x - x'|, periodic or not.
  EXPECT_EQ(Geometry::chain(20).distance(1, 0, 19, 0), 18.0);
  EXPECT_EQ(Geometry::chain(20).max_distance(), 19.0);
}

// The Mogi picture on a lattice: a foreshock's band is its Euclidean distance from the
// mainshock's trigger (x, y), and the exposure counts the lattice's sites per band.
TEST(SeismicityGeometry, SpaceTimeOnALatticeBandsByPlaneDistance) {
  const Geometry g{30, 20, false, false};  // largest distance sqrt(29^2 + 19^2) = 34.7
  SeismicityOptions o;
  o.blocks = g.nx;
  o.geometry = g;
  o.mainshock.blocks = g.nx;
  o.mainshock.mu = 5.0;
  Seismicity s(o);
  auto at = [](double t, double mu, int x, int y) {
    Quake q;
    q.t = t;
    q.mu = mu;
    q.moment = std::exp(mu);
    q.trigger = q.first = q.last = x;
    q.trigger_row = y;
    q.blocks = 1;
    return q;
  };
  s.add(at(0.0, 6.0, 0, 0));  // a mainshock opens the window
  // A foreshock 3 columns and 4 rows from the next mainshock: distance 5, not 3 (the
  // along-strike distance a chain would use).
  s.add(at(1.0, 0.5, 13, 14));
  s.add(at(2.0, 6.0, 10, 10));
  s.finish();
  const SpaceTime& st = s.spacetime();
  EXPECT_EQ(st.band_width(), 4);  // 35 distances 0..34 in bands of 4
  EXPECT_EQ(st.bands(), 9);
  double in_band1 = 0, total = 0;
  for (std::size_t i = 0; i < st.count().size(); ++i) {
    in_band1 += st.count()[i][1];
    for (double c : st.count()[i]) total += c;
  }
  EXPECT_EQ(in_band1, 1.0);  // floor(5) / 4 = 1
  EXPECT_EQ(total, 1.0);
  // Exposure: each time bin the window covers, split over the bands as the sites are.
  for (std::size_t i = 0; i < st.exposure().size(); ++i) {
    double row = 0;
    for (double e : st.exposure()[i]) row += e;
    if (row > 0) {
      // Band 0 (distances 0..3.99 from (10, 10)) holds the sites with dx^2 + dy^2 < 16.
      int near = 0;
      for (int y = 0; y < g.ny; ++y)
        for (int x = 0; x < g.nx; ++x) near += (x - 10) * (x - 10) + (y - 10) * (y - 10) < 16;
      EXPECT_NEAR(st.exposure()[i][0] / row, near / 600.0, 1e-12);
    }
  }
}

}  // namespace
}  // namespace bkq::seis
