// Implementation of the fit table and JSON (see gr_report.hpp).
#include "app/gr_report.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <utility>

#include "core/format.hpp"

namespace bkq {

namespace {

std::string fixed(double x, int digits = 4) {
  if (!std::isfinite(x)) return format_real(x);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, x);
  return buf;
}
std::string pm(double b, double err) {
  return fixed(b) + " +/- " + fixed(err);
}
// Sets each key to its value as a fit number, in the order given.
Json& set_fit_numbers(Json& o, std::initializer_list<std::pair<const char*, double>> numbers) {
  for (const auto& [key, x] : numbers) o.set(key, fit_number(x));
  return o;
}
}  // namespace

static std::string two_laws_and_notes(const GrFit& f);

Json gr_fit_json(const GrFit& f) {
  Json two = Json::object(), excess = Json::object(), o = Json::object();
  two.set("ok", f.two_law_ok);
  set_fit_numbers(two, {{"b1", f.two_law_b1},
                        {"b2", f.two_law_b2},
                        {"mu_cross", f.two_law_mu_cross},
                        {"moment_cross", f.two_law_moment_cross},
                        {"ln_A1", f.two_law_ln_A1},
                        {"ln_A2", f.two_law_ln_A2},
                        {"mu_low", f.two_law_mu_low},
                        {"mu_high", f.two_law_mu_high}});
  excess.set("found", f.excess_found)
      .set("mu", fit_number(f.excess_found ? f.excess_mu : NAN))
      .set("observed", f.excess_observed)
      .set("expected", fit_number(f.excess_expected))
      .set("count", fit_number(f.excess_count));
  o.set("b_ok", f.b_ok);
  if (!f.b_ok) o.set("no_b_reason", f.no_b_reason);
  o.set("bin_width", fit_number(f.bin_width))
      .set("events", f.n_total)
      .set("mu_min", fit_number(f.mu_min))
      .set("mu_max", fit_number(f.mu_max))
      .set("window_auto", f.window_auto)
      .set("mu_max_auto", f.mu_max_auto)
      .set("truncated", f.truncated)
      .set("n_in_window", f.n_in_window);
  set_fit_numbers(o, {{"b_mle", f.b_mle},
                      {"b_mle_err", f.b_mle_err},
                      {"b_mle_sys_err", f.b_mle_sys_err},
                      {"b_mw", b_moment_magnitude(f.b_mle)},
                      {"b_mw_err", b_moment_magnitude(f.b_mle_err)},
                      {"b_mw_sys_err", b_moment_magnitude(f.b_mle_sys_err)}});
  o.set("sys_windows", f.sys_windows);
  set_fit_numbers(o, {{"b_aki", f.b_aki},
                      {"b_aki_err", f.b_aki_err},
                      {"b_lsq", f.b_lsq},
                      {"b_lsq_err", f.b_lsq_err},
                      {"ln_A", f.ln_A},
                      {"ks_distance", f.ks_distance}})
      .set("two_power_law", two)
      .set("excess", excess)
      .set("notes", Json::strings(f.notes));
  return o;
}

Json class_counts_json(const EventClassCounts& c) {
  Json o = Json::object();
  o.set("single_block", c.single_block)
      .set("localised", c.localised)
      .set("delocalised", c.delocalised)
      .set("single_block_fraction", fit_number(c.fraction(EventClass::single_block)))
      .set("localised_fraction", fit_number(c.fraction(EventClass::localised)))
      .set("delocalised_fraction", fit_number(c.fraction(EventClass::delocalised)));
  return o;
}

std::string gr_fit_table(const GrFit& f) {
  std::string t;
  t += "events            " + std::to_string(f.n_total) + "\n";
  t += "window            [" + fixed(f.mu_min, 3) + ", " + fixed(f.mu_max, 3) + ")  " +
       std::to_string(f.n_in_window) + " events, " +
       (f.window_auto ? (f.mu_max_auto ? "mu_min and mu_max automatic" : "mu_min automatic")
                      : (f.mu_max_auto ? "mu_min given, mu_max automatic" : "mu_min given")) +
       (f.truncated ? ", truncated at mu_max" : "") + "\n";
  t += "bin width         " + fixed(f.bin_width, 3) + "\n";
  if (!f.b_ok) {
    t += "b                 none: " + f.no_b_reason + "\n";
    t += two_laws_and_notes(f);
    return t;
  }
  t += "b  binned MLE     " + pm(f.b_mle, f.b_mle_err) + " (stat.) +/- " + fixed(f.b_mle_sys_err) +
       " (sys.)   per unit of mu = ln M (Tinti & Mulargia 1987; Shi & "
       "Bolt error; sys.: half the range of b over " +
       std::to_string(f.sys_windows) + " nearby windows)\n";
  t += "b_mw              " + pm(b_moment_magnitude(f.b_mle), b_moment_magnitude(f.b_mle_err)) +
       " (stat.) +/- " + fixed(b_moment_magnitude(f.b_mle_sys_err)) +
       " (sys.)   per unit of Mw = (2/3) log10 M + const (= 1.5 b)\n";
  if (std::isnan(f.b_aki))
    t += "b  unbinned MLE   n/a (needs the magnitudes themselves, not a histogram)\n";
  else
    t += "b  unbinned MLE   " + pm(f.b_aki, f.b_aki_err) + "   (Aki 1965)\n";
  t += "b  least squares  " + pm(f.b_lsq, f.b_lsq_err) + "   (slope of ln R, weights R)\n";
  t += "KS distance       " + fixed(f.ks_distance) + "\n";
  return t + two_laws_and_notes(f);
}

// The lines after the b estimates: two power laws, excess, notes.
static std::string two_laws_and_notes(const GrFit& f) {
  std::string t;
  if (f.two_law_ok)
    t += "two power laws    b1 = " + fixed(f.two_law_b1) + ", b2 = " + fixed(f.two_law_b2) +
         ", crossover mu~ = " + fixed(f.two_law_mu_cross, 3) +
         " (M~ = " + fixed(f.two_law_moment_cross, 3) + ")   (thesis eq. 2.10)\n";
  else
    t += "two power laws    not fitted\n";
  if (!f.b_ok)
    t += "large-event excess not tested (no fitted line)\n";
  else if (f.excess_found)
    t += "large-event excess above mu = " + fixed(f.excess_mu, 3) + ": " +
         std::to_string(f.excess_observed) + " observed, " + fixed(f.excess_expected, 1) +
         " expected; up to " + fixed(f.excess_count, 1) + " events beyond the line\n";
  else
    t += "large-event excess none (> 2 sigma Poisson)\n";
  for (const auto& n : f.notes) t += "note: " + n + "\n";
  return t;
}

std::string class_counts_table(const EventClassCounts& c) {
  auto line = [&](const char* name, std::int64_t k, EventClass e) {
    return std::string(name) + std::to_string(k) + " (" + fixed(100 * c.fraction(e), 1) + " %)\n";
  };
  return line("single-block      ", c.single_block, EventClass::single_block) +
         line("localised         ", c.localised, EventClass::localised) +
         line("delocalised       ", c.delocalised, EventClass::delocalised);
}

}  // namespace bkq
