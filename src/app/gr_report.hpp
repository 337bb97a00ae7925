// Presentation of a Gutenberg-Richter fit: the short human table printed by `bkquake fit`
// and the JSON object (io/json.hpp, the one JSON writer) written by `bkquake fit --json`
// and `bkquake merge`. The statistics compute; this file only formats.
#pragma once

#include <string>

#include "io/json.hpp"
#include "stats/event_classes.hpp"
#include "stats/gutenberg_richter.hpp"
#include "stats/power_law.hpp"

namespace bkq {

// The fit as a JSON object; reals are written shortest round-trip ("mu_min": -8) and
// non-finite ones as null.
Json gr_fit_json(const GrFit& f);
Json class_counts_json(const EventClassCounts& c);
// A power-law fit of a size measure as summary.json's and fit --json's "tau": measure,
// value (tau), err (block bootstrap), x_min, x_max (null: none), p, and the rest.
Json power_law_json(const PowerLawFit& f, const std::string& measure);
std::string power_law_table(const PowerLawFit& f, const std::string& measure);
// A real written as the fit reports write it (Json::Real::shortest).
inline Json fit_number(double x) {
  return Json::number(x, Json::Real::shortest);
}

// Why a run or a merge has no fit when it holds fewer than two events (summary.json's
// fit_error, and the line printed about it).
inline constexpr const char* kTooFewToFit = "fewer than 2 events";

// Human-readable block of lines (trailing newline included).
std::string gr_fit_table(const GrFit& f);
std::string class_counts_table(const EventClassCounts& c);

}  // namespace bkq
