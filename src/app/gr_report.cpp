// Implementation of the fit table and JSON (see gr_report.hpp).
#include "app/gr_report.hpp"
#include "core/format.hpp"

#include <cmath>
#include <cstdio>

#include "io/csv_util.hpp"

namespace bkq {

namespace {
const std::string kNested = "\x01nested";

std::string fixed(double x, int digits = 4) {
  if (!std::isfinite(x)) return format_real(x);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, x);
  return buf;
}
std::string pm(double b, double err) {
  return fixed(b) + " +/- " + fixed(err);
}
}  // namespace

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string json_number(double x) {
  return std::isfinite(x) ? format_real(x) : "null";
}

JsonObject& JsonObject::add(const std::string& key, double x) {
  raw_.emplace_back(key, json_number(x));
  return *this;
}
JsonObject& JsonObject::add(const std::string& key, std::int64_t i) {
  raw_.emplace_back(key, std::to_string(i));
  return *this;
}
JsonObject& JsonObject::add(const std::string& key, bool b) {
  raw_.emplace_back(key, b ? "true" : "false");
  return *this;
}
JsonObject& JsonObject::add(const std::string& key, const std::string& s) {
  raw_.emplace_back(key, json_string(s));
  return *this;
}
JsonObject& JsonObject::add(const std::string& key, const JsonObject& o) {
  raw_.emplace_back(key, kNested + std::to_string(nested_.size()));
  nested_.push_back(o);
  return *this;
}
JsonObject& JsonObject::add(const std::string& key, const std::vector<std::string>& strings) {
  std::string text = "[";
  for (std::size_t i = 0; i < strings.size(); ++i)
    text += (i ? ", " : "") + json_string(strings[i]);
  raw_.emplace_back(key, text + "]");
  return *this;
}

std::string JsonObject::str(int indent) const {
  if (raw_.empty()) return "{}";
  const std::string pad(static_cast<std::size_t>(indent) + 2, ' ');
  std::string out = "{\n";
  for (std::size_t i = 0; i < raw_.size(); ++i) {
    const auto& [key, text] = raw_[i];
    out += pad + json_string(key) + ": ";
    if (text.rfind(kNested, 0) == 0)
      out += nested_[std::stoul(text.substr(kNested.size()))].str(indent + 2);
    else
      out += text;
    out += i + 1 < raw_.size() ? ",\n" : "\n";
  }
  return out + std::string(static_cast<std::size_t>(indent), ' ') + "}";
}

JsonObject gr_fit_json(const GrFit& f) {
  JsonObject two, excess, o;
  two.add("ok", f.two_law_ok)
      .add("b1", f.two_law_b1)
      .add("b2", f.two_law_b2)
      .add("mu_cross", f.two_law_mu_cross)
      .add("moment_cross", f.two_law_moment_cross)
      .add("ln_A1", f.two_law_ln_A1)
      .add("ln_A2", f.two_law_ln_A2)
      .add("mu_low", f.two_law_mu_low)
      .add("mu_high", f.two_law_mu_high);
  excess.add("found", f.excess_found)
      .add("mu", f.excess_found ? f.excess_mu : NAN)
      .add("observed", f.excess_observed)
      .add("expected", f.excess_expected)
      .add("count", f.excess_count);
  o.add("bin_width", f.bin_width)
      .add("events", f.n_total)
      .add("mu_min", f.mu_min)
      .add("mu_max", f.mu_max)
      .add("window_auto", f.window_auto)
      .add("mu_max_auto", f.mu_max_auto)
      .add("truncated", f.truncated)
      .add("n_in_window", f.n_in_window)
      .add("b_mle", f.b_mle)
      .add("b_mle_err", f.b_mle_err)
      .add("b_aki", f.b_aki)
      .add("b_aki_err", f.b_aki_err)
      .add("b_lsq", f.b_lsq)
      .add("b_lsq_err", f.b_lsq_err)
      .add("ln_A", f.ln_A)
      .add("ks_distance", f.ks_distance)
      .add("two_power_law", two)
      .add("excess", excess)
      .add("notes", f.notes);
  return o;
}

JsonObject class_counts_json(const EventClassCounts& c) {
  JsonObject o;
  o.add("single_block", c.single_block)
      .add("localised", c.localised)
      .add("delocalised", c.delocalised)
      .add("single_block_fraction", c.fraction(EventClass::single_block))
      .add("localised_fraction", c.fraction(EventClass::localised))
      .add("delocalised_fraction", c.fraction(EventClass::delocalised));
  return o;
}

std::string gr_fit_table(const GrFit& f) {
  std::string t;
  t += "events            " + std::to_string(f.n_total) + "\n";
  t += "window            [" + fixed(f.mu_min, 3) + ", " + fixed(f.mu_max, 3) + ")  " +
       std::to_string(f.n_in_window) + " events, " +
       (f.window_auto ? (f.mu_max_auto ? "mu_min and mu_max by KS scan"
                                       : "mu_min by KS scan (Clauset et al. 2009)")
                      : (f.mu_max_auto ? "mu_min given, mu_max by KS scan" : "mu_min given")) +
       (f.truncated ? ", truncated at mu_max" : "") + "\n";
  t += "bin width         " + fixed(f.bin_width, 3) + "\n";
  t += "b  binned MLE     " + pm(f.b_mle, f.b_mle_err) +
       "   (Tinti & Mulargia 1987; Shi & Bolt error)\n";
  if (std::isnan(f.b_aki))
    t += "b  unbinned MLE   n/a (needs the magnitudes themselves, not a histogram)\n";
  else
    t += "b  unbinned MLE   " + pm(f.b_aki, f.b_aki_err) + "   (Aki 1965)\n";
  t += "b  least squares  " + pm(f.b_lsq, f.b_lsq_err) + "   (slope of ln R, weights R)\n";
  t += "KS distance       " + fixed(f.ks_distance) + "\n";
  if (f.two_law_ok)
    t += "two power laws    b1 = " + fixed(f.two_law_b1) + ", b2 = " + fixed(f.two_law_b2) +
         ", crossover mu~ = " + fixed(f.two_law_mu_cross, 3) +
         " (M~ = " + fixed(f.two_law_moment_cross, 3) + ")   (thesis eq. 2.10)\n";
  else
    t += "two power laws    not fitted\n";
  if (f.excess_found)
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
