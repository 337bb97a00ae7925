// The files of `bkquake seismicity`; see seismicity_csv.hpp.
#include "io/seismicity_csv.hpp"

#include <array>
#include <cmath>

#include "core/format.hpp"

namespace bkq {

namespace {

using seis::LogBins;

const char* kTimeUnits = "clock";  // load (event runs) or episode start (continuous runs)

std::string head(const Schema& schema, const std::vector<std::string>& comments) {
  std::string out;
  for (const auto& c : comments) out += "# " + c + "\n";
  out += header_of(schema) + "\n";
  return out;
}

// A row from cells already formatted.
void row(std::string& out, std::initializer_list<std::string> cells) {
  bool first = true;
  for (const auto& c : cells) {
    if (!first) out += ',';
    out += c;
    first = false;
  }
  out += '\n';
}

std::string r(double x) {
  return format_real(x);
}
std::string i(std::int64_t x) {
  return std::to_string(x);
}
std::string i(double x) {
  return std::to_string(static_cast<std::int64_t>(std::llround(x)));
}

// [first, last] bins holding something, or first > last.
template <class V>
std::pair<std::size_t, std::size_t> filled(const V& v) {
  std::size_t a = v.size(), b = 0;
  for (std::size_t k = 0; k < v.size(); ++k)
    if (v[k] > 0) {
      a = std::min(a, k);
      b = k;
    }
  return {a, b};
}

}  // namespace

const Schema& interevent_schema() {
  static const Schema s = {
      {"subset", "", "the events whose waiting times these are: all, mu>=X, mainshocks", kText},
      {"t_low", kTimeUnits, "lower edge of the waiting-time bin (10 a decade)"},
      {"t_high", kTimeUnits, "upper edge"},
      {"count", "", "waiting times in [t_low, t_high)", kInteger},
      {"pdf", "1/clock", "count / (waiting times of the subset * bin width)"},
      {"poisson_pdf", "1/clock",
       "the exponential law of a Poisson process with the subset's mean, averaged over the bin"},
  };
  return s;
}

const Schema& recurrence_schema() {
  static const Schema s = {
      {"scope", "",
       "system: between consecutive mainshocks; block: until a block is inside a mainshock's "
       "slipped extent again",
       kText},
      {"t_low", kTimeUnits, "lower edge of the interval bin (50 a decade)"},
      {"t_high", kTimeUnits, "upper edge"},
      {"count", "", "intervals in [t_low, t_high)", kInteger},
      {"pdf", "1/clock", "count / (intervals * bin width)"},
      {"weibull_pdf", "1/clock", "the maximum-likelihood Weibull law, averaged over the bin"},
      {"lognormal_pdf", "1/clock", "the maximum-likelihood lognormal law, averaged over the bin"},
      {"cond_prob", "",
       "probability that the next mainshock comes in [t_low, t_high) when none has by t_low: "
       "count / intervals >= t_low"},
      {"weibull_cond_prob", "", "the same from the Weibull law: 1 - S(t_high)/S(t_low)"},
  };
  return s;
}

const Schema& omori_schema() {
  static const Schema s = {
      {"side", "", "after: time since the mainshock; before: time before it", kText},
      {"t_low", kTimeUnits, "lower edge of the time bin (10 a decade)"},
      {"t_high", kTimeUnits, "upper edge"},
      {"count", "", "events of all sequences in the bin", kInteger},
      {"sequences", "", "windows covering the bin (fractional at a window's end)"},
      {"rate", "1/clock", "stacked rate per sequence: count / (sequences * bin width)"},
      {"fit_rate", "1/clock",
       "the fitted mu + K/(t + c)^p averaged over the bin (the background rate alone when "
       "there is no excess)"},
      {"bath_delta_mu", "",
       "after: mean over sequences of mu_main - the largest aftershock's mu by t_high (nan "
       "before)"},
      {"bath_sequences", "", "after: sequences with an aftershock by t_high", kInteger},
  };
  return s;
}

const Schema& moment_rate_schema() {
  static const Schema s = {
      {"t_low", kTimeUnits, "lower edge of the time bin (equal bins from the first event)"},
      {"t_high", kTimeUnits, "upper edge"},
      {"events", "", "events in the bin", kInteger},
      {"moment", "length", "moment released in the bin"},
      {"rate", "length/clock", "moment / bin width"},
  };
  return s;
}

const Schema& scaling_schema() {
  static const Schema s = {
      {"quantity", "", "length: last_block - first_block + 1 (blocks); duration", kText},
      {"x_low", "blocks or time", "lower edge of the bin (10 a decade)"},
      {"x_high", "blocks or time", "upper edge"},
      {"events", "", "events in the bin", kInteger},
      {"mean_moment", "length", "mean moment of the bin's events"},
      {"geo_mean_moment", "length", "exp(mean ln M) of the bin's events"},
      {"fit_moment", "length",
       "the power law fitted to the bins' mean ln M (bins of 3 events or more) at the "
       "bin's geometric centre (exponent in seismicity.json)"},
  };
  return s;
}

const Schema& spacetime_schema() {
  static const Schema s = {
      {"table", "",
       "density: events before mainshocks against distance and time; b: their b-value "
       "against time before the mainshock",
       kText},
      {"t_low", kTimeUnits, "lower edge of the time before the mainshock (2 bins a decade)"},
      {"t_high", kTimeUnits, "upper edge"},
      {"d_low", "blocks",
       "density: lower edge of the distance between the event's and the mainshock's trigger "
       "block (a lattice's: Euclidean between trigger sites, in site spacings) (nan for b)"},
      {"d_high", "blocks", "density: upper edge (exclusive)"},
      {"events", "", "events in the cell (b: with mu >= mu_c)", kInteger},
      {"density", "1/(block clock)",
       "events / (sum over mainshocks of the blocks (a lattice's sites) at that distance * "
       "covered time)"},
      {"b", "", "Aki's b of the events with mu >= mu_c (seismicity.json) (nan for density)"},
      {"b_err", "", "its standard error b / sqrt(events)"},
  };
  return s;
}

const Schema& seismicity_export_schema() {
  static const Schema s = {
      {"time", kTimeUnits, "the event's time: load (event runs) or episode start (continuous)"},
      {"Mw", "",
       "moment magnitude (2/3) log10(moment) + C (C from --mw-offset, default 0); the "
       "catalogue's mu = ln(moment) = 1.5 ln(10) (Mw - C)"},
      {"x", "blocks", "position along strike: the trigger (hypocentre) block"},
      {"length", "blocks", "rupture length: last_block - first_block + 1 (or blocks)", kInteger},
      {"mu", "", "ln(moment), bkquake's magnitude"},
      {"event", "", "the catalogue's event number", kInteger},
  };
  return s;
}

const Schema& event_slip_schema(SlipLayout layout) {
  // The four layouts, each built once: [rows + 2 topplings].
  static const std::array<Schema, 4> all = [] {
    std::array<Schema, 4> a;
    for (int k = 0; k < 4; ++k) {
      const bool rows = k & 1, topplings = k & 2;
      Schema& s = a[k];
      s.push_back({"event", "", "the catalogue's event number", kInteger});
      if (rows)
        s.push_back({"block", "",
                     "column x (0-based, along strike, model.blocks) of a site that slipped in "
                     "the event",
                     kInteger});
      else
        s.push_back({"block", "", "0-based index of a block that slipped in the event", kInteger});
      if (rows)
        s.push_back({"row", "", "its row y (0-based, across strike, model.rows)", kInteger});
      if (topplings)
        s.push_back({"slip", "stress",
                     "the stress the site released over the event: the sum over its topplings "
                     "of the stress it held; an event's values sum to its moment"});
      else
        s.push_back(
            {"slip", "length", "its slip over the event; the event's slips sum to its moment"});
      if (topplings)
        s.push_back({"topplings", "", "how many times the site toppled in the event", kInteger});
    }
    return a;
  }();
  return all[(layout.rows ? 1 : 0) + (layout.topplings ? 2 : 0)];
}

std::vector<std::pair<std::string, const Schema*>> seismicity_schemas() {
  return {{"interevent.csv", &interevent_schema()}, {"recurrence.csv", &recurrence_schema()},
          {"omori.csv", &omori_schema()},           {"moment_rate.csv", &moment_rate_schema()},
          {"scaling.csv", &scaling_schema()},       {"spacetime.csv", &spacetime_schema()},
          {"export", &seismicity_export_schema()},  {"event_slip.csv", &event_slip_schema()}};
}

std::string interevent_csv(const seis::Seismicity& s, const std::vector<std::string>& comments) {
  std::string out = head(interevent_schema(), comments);
  const LogBins& bins = s.interevent().bins();
  for (const auto& w : s.interevent().subsets()) {
    const double n = static_cast<double>(w.moments.n());
    if (n < 1) continue;
    const double tau = w.moments.mean();
    const auto [a, b] = filled(w.counts);
    for (std::size_t k = a; k <= b && k < w.counts.size(); ++k) {
      const double lo = bins.low(k), hi = bins.high(k), width = hi - lo;
      const double poisson = tau > 0 ? (std::exp(-lo / tau) - std::exp(-hi / tau)) / width : NAN;
      row(out, {w.subset, r(lo), r(hi), i(w.counts[k]),
                r(static_cast<double>(w.counts[k]) / (n * width)), r(poisson)});
    }
  }
  return out;
}

std::string recurrence_csv(const seis::Seismicity& s, const std::vector<std::string>& comments) {
  std::string out = head(recurrence_schema(), comments);
  const LogBins& bins = s.recurrence().bins();
  auto scope = [&](const char* name, const seis::Intervals& iv, const seis::WeibullFit& w,
                   const seis::LognormalFit& l) {
    const double n = static_cast<double>(iv.moments.n());
    if (n < 1) return;
    const auto [a, b] = filled(iv.counts);
    double remaining = n;
    for (std::size_t k = 0; k < a; ++k) remaining -= static_cast<double>(iv.counts[k]);
    for (std::size_t k = a; k <= b && k < iv.counts.size(); ++k) {
      const double lo = bins.low(k), hi = bins.high(k), width = hi - lo;
      const double c = static_cast<double>(iv.counts[k]);
      const double wp = w.ok ? (w.survival(lo) - w.survival(hi)) / width : NAN;
      const double lp = l.ok ? (l.cdf(hi) - l.cdf(lo)) / width : NAN;
      const double wc = w.ok && w.survival(lo) > 0 ? 1 - w.survival(hi) / w.survival(lo) : NAN;
      row(out, {name, r(lo), r(hi), i(iv.counts[k]), r(c / (n * width)), r(wp), r(lp),
                r(remaining > 0 ? c / remaining : NAN), r(wc)});
      remaining -= c;
    }
  };
  scope("system", s.recurrence().system(), s.weibull(), s.lognormal());
  scope("block", s.recurrence().per_block(), s.block_weibull(), s.block_lognormal());
  return out;
}

std::string omori_csv(const seis::Seismicity& s, const std::vector<std::string>& comments) {
  std::string out = head(omori_schema(), comments);
  const LogBins& bins = s.omori().bins();
  auto side = [&](const char* name, const seis::Stack& st, const seis::OmoriFit& f, bool after) {
    const auto [a, b] = filled(st.count);
    for (std::size_t k = a; k <= b && k < st.count.size(); ++k) {
      const double lo = bins.low(k), hi = bins.high(k), width = hi - lo, e = st.exposure[k];
      double fit = f.background_only;
      if (f.excess) {
        const double q = 1 - f.p.value, c = f.c.value;
        const double I = std::abs(q) < 1e-12 ? std::log((hi + c) / (lo + c))
                                             : (std::pow(hi + c, q) - std::pow(lo + c, q)) / q;
        fit = f.background.value + f.K.value * I / width;
      }
      const auto nb = after ? s.omori().bath_sequences()[k] : 0;
      row(out,
          {name, r(lo), r(hi), i(st.count[k]), r(e), r(e > 0 ? st.count[k] / (e * width) : NAN),
           r(fit), r(after && nb > 0 ? s.omori().bath_sum()[k] / static_cast<double>(nb) : NAN),
           i(nb)});
    }
  };
  side("before", s.omori().before(), s.foreshocks(), false);
  side("after", s.omori().after(), s.aftershocks(), true);
  return out;
}

std::string moment_rate_csv(const seis::Seismicity& s, const std::vector<std::string>& comments) {
  std::string out = head(moment_rate_schema(), comments);
  const auto& m = s.moment_rate();
  for (std::size_t k = 0; k < m.moment().size(); ++k) {
    const double lo = m.t0() + static_cast<double>(k) * m.width();
    row(out, {r(lo), r(lo + m.width()), i(m.events()[k]), r(m.moment()[k]),
              r(m.moment()[k] / m.width())});
  }
  return out;
}

std::string scaling_csv(const seis::Seismicity& s, const std::vector<std::string>& comments) {
  std::string out = head(scaling_schema(), comments);
  auto axis = [&](const char* name, const seis::ScalingAxis& ax, const LogBins& bins) {
    const auto [a, b] = filled(ax.events);
    const seis::LineFit fit = ax.binned_fit();
    for (std::size_t k = a; k <= b && k < ax.events.size(); ++k) {
      if (ax.events[k] == 0) continue;
      const double n = static_cast<double>(ax.events[k]);
      const double lo = bins.low(k), hi = bins.high(k);
      const double x = lo > 0 ? std::sqrt(lo * hi) : 0.5 * hi;
      row(out, {name, r(lo), r(hi), i(ax.events[k]), r(ax.sum_moment[k] / n),
                r(std::exp(ax.sum_log_moment[k] / n)),
                r(std::exp(fit.intercept() + fit.slope() * std::log(x)))});
    }
  };
  axis("length", s.scaling().length(), s.scaling().length_bins());
  axis("duration", s.scaling().duration(), s.scaling().duration_bins());
  return out;
}

std::string spacetime_csv(const seis::Seismicity& s, const std::vector<std::string>& comments) {
  std::string out = head(spacetime_schema(), comments);
  const auto& st = s.spacetime();
  const LogBins& bins = st.bins();
  const double nan = NAN;
  for (std::size_t k = 0; k < bins.size(); ++k) {
    double n = 0, e = 0;
    for (std::size_t d = 0; d < st.count()[k].size(); ++d) {
      n += st.count()[k][d];
      e += st.exposure()[k][d];
    }
    if (!(e > 0)) continue;
    for (std::size_t d = 0; d < st.count()[k].size(); ++d) {
      const double ex = st.exposure()[k][d];
      row(out,
          {"density", r(bins.low(k)), r(bins.high(k)), r(static_cast<double>(d) * st.band_width()),
           r(static_cast<double>(d + 1) * st.band_width()), i(st.count()[k][d]),
           r(ex > 0 ? st.count()[k][d] / ex : nan), r(nan), r(nan)});
    }
  }
  for (std::size_t k = 0; k < bins.size(); ++k) {
    const auto& m = st.before()[k];
    const double all = m.events();
    if (!(all > 0)) continue;
    const seis::Estimate b = m.b(s.b_mu_min());
    double above = 0;
    for (int j = seis::MagSums::bin(s.b_mu_min() + 1e-9 * seis::MagSums::kWidth);
         j < seis::MagSums::kBins; ++j)
      above += m.count[static_cast<std::size_t>(j)];
    row(out, {"b", r(bins.low(k)), r(bins.high(k)), r(nan), r(nan), i(above), r(nan), r(b.value),
              r(b.err)});
  }
  return out;
}

std::string seismicity_export_row(const seis::Quake& q, double mw_offset) {
  std::string out;
  out += format_real(q.t);
  out += ',';
  out += format_real(seis::mw_of_moment(q.moment, mw_offset));
  out += ',';
  out += std::to_string(q.trigger);
  out += ',';
  out += std::to_string(q.length());
  out += ',';
  out += format_real(q.mu);
  out += ',';
  out += std::to_string(q.event);
  return out;
}

}  // namespace bkq
