// `bkquake seismicity RUN_DIR|CATALOG`: the statistics beyond Gutenberg-Richter
// (stats/seismicity/) from any event catalogue (catalog.csv or catalog.h5, read through
// io/catalog_reader.hpp in one streaming pass), written as the files of io/seismicity_csv.hpp
// and seismicity.json into RUN_DIR/seismicity/ (or beside a bare catalogue, or --out).
// Writing into a folder takes its lock (io/folder_lock.hpp; a stale one, of a killed
// command, taken over) before anything is read, and replaces only the seismicity/ folder, as
// a whole (built beside it, then swapped in); the export is a derived output
// (io/run_folder.hpp), never over the input or a run's files.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "stats/seismicity/seismicity.hpp"

namespace bkq {

struct SeismicityRequest {
  std::string input;  // a run folder, a sweep folder or a catalogue file
  std::string out;    // default: <run folder or the catalogue's folder>/seismicity
  std::optional<double> mainshock_mu;
  std::optional<int> blocks;  // N when no scene.ini is beside the catalogue
  std::optional<double> b_mu_min;
  std::optional<std::vector<double>> interevent_mu;
  std::string export_file;  // also write the catalogue in seismology's conventions
  double mw_offset = 0;     // C of Mw = (2/3) log10 M + C
};

struct SeismicityReport {
  std::string catalog, out, clock, blocks_from;
  double seconds = 0;
  std::string json;  // seismicity.json as written
};

// The run folders a request covers: the folder itself, or each replica of a sweep folder
// that kept its catalogue (SWEEP/points/pNNNN/rNN, beside SWEEP/sweep.csv). bkq::Error for a merged
// folder (no single clock: each merged run's load starts afresh; it names the runs to analyse
// instead).
std::vector<std::string> seismicity_inputs(const std::string& input);

// Analyses one catalogue (a run folder or a catalogue file). `log` gets the progress lines
// (the mainshock rule, the headline numbers).
SeismicityReport seismicity_of(const SeismicityRequest& req, std::ostream& log);

}  // namespace bkq
