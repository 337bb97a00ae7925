// The files of `bkquake seismicity` (app/seismicity.hpp): each one's columns declared once
// here, and the whole text of each written from the analysis (stats/seismicity/). Every
// file starts with '#' lines (what it holds, the input, provenance), then the header.
// The docs page docs/explanation/seismicity.md carries the column tables, checked against
// these schemas by tests/regression/test_seismicity.cpp.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "io/schema.hpp"
#include "stats/seismicity/seismicity.hpp"

namespace bkq {

const Schema& interevent_schema();
const Schema& recurrence_schema();
const Schema& omori_schema();
const Schema& moment_rate_schema();
const Schema& scaling_schema();
const Schema& spacetime_schema();
// The catalogue in seismology's column conventions (`bkquake seismicity --export FILE`).
const Schema& seismicity_export_schema();

// event_slip.csv of a run with output.event_slip: the slip of each block (a lattice's
// site) of each event with mu >= the threshold, long form. Its columns beyond
// event,block,slip: `row` (after block) on a lattice of more than one row, where block is
// the site's column x along strike; `topplings` (last) for the OFC automaton, whose slip is
// the stress a site released. A chain has neither.
struct SlipLayout {
  bool rows = false;
  bool topplings = false;
};
const Schema& event_slip_schema(SlipLayout layout = {});

// (file name, schema) of every file above, in the docs' order.
std::vector<std::pair<std::string, const Schema*>> seismicity_schemas();

// Each file's whole text: `comments` as '# ' lines, the header, the rows.
std::string interevent_csv(const seis::Seismicity& s, const std::vector<std::string>& comments);
std::string recurrence_csv(const seis::Seismicity& s, const std::vector<std::string>& comments);
std::string omori_csv(const seis::Seismicity& s, const std::vector<std::string>& comments);
std::string moment_rate_csv(const seis::Seismicity& s, const std::vector<std::string>& comments);
std::string scaling_csv(const seis::Seismicity& s, const std::vector<std::string>& comments);
std::string spacetime_csv(const seis::Seismicity& s, const std::vector<std::string>& comments);
// One row of the export (no newline); `mw_offset`: the constant of Mw.
std::string seismicity_export_row(const seis::Quake& q, double mw_offset);

}  // namespace bkq
