// `bkquake stability`: the sliding equilibrium of a scene at its disc speed
// (drive.speed), the eigenvalues of its linearisation (stats/stability.hpp), optionally
// over a sweep of one scene key, written to stability.csv, stability_summary.csv and, for
// the modes asked for, modes.csv. Also the start of a continuous run at the sliding
// equilibrium plus a small perturbation along one mode (run.start = equilibrium).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/scene.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"
#include "model/equilibrium.hpp"
#include "stats/stability.hpp"

namespace bkq {

// --sweep KEY=FROM:TO:COUNT (COUNT values, ends included; geometric with log).
struct StabilitySweep {
  std::string key;
  double from = 0, to = 0;
  int count = 1;
  bool log = false;
};
StabilitySweep parse_sweep(const std::string& text, bool log);

// FAMILY,INDEX (chain,3  pad,0  1dof,0).
struct ModeSelect {
  ModeFamily family = ModeFamily::Chain;
  int index = 0;
  bool operator==(const ModeSelect&) const = default;
};
ModeSelect parse_mode(const std::string& text, const std::string& what);

struct StabilityOptions {
  std::optional<StabilitySweep> sweep;
  bool dense = false;              // the dense state matrix instead of the modal reduction
  std::vector<ModeSelect> shapes;  // modes whose shapes go to modes.csv
};

struct StabilityPoint {
  double value = 0;  // of the swept key (drive.speed without a sweep)
  double speed = 0;
  SlidingEquilibrium equilibrium;  // without the block displacements (u is emptied)
  std::vector<Eigenmode> modes;
  std::vector<std::pair<Eigenmode, ModeShape>> shapes;
};

// Largest N the dense solver is used for (O(N^3): N = 400 takes seconds).
inline constexpr int kDenseLimit = 1000;

// The analysis at each value; throws bkq::Error (naming the key and value) when a value
// has no sliding equilibrium, a key cannot be swept or a mode does not exist.
std::vector<StabilityPoint> run_stability(const Scene& scene, const StabilityOptions& opt);

// The CSV texts of the three outputs (header first).
std::string stability_csv(const std::vector<StabilityPoint>& points);
std::string stability_summary_csv(const std::vector<StabilityPoint>& points);
std::string modes_csv(const std::vector<StabilityPoint>& points);

// "chain:3".
std::string mode_name(const Eigenmode& m);

// The mode `sel` of the scene's linearisation at speed v (the one with Im lambda >= 0 and,
// for an overdamped mode, the larger real root); throws bkq::Error when it has none.
// Throws bkq::Error where the modal reduction (stats/stability.hpp) is not exact: range
// coupling with free ends.
void check_modal_reduction(const ModelParams& p);
std::pair<Eigenmode, ModeShape> find_mode(const ModelParams& p, double slope, ModeSelect sel);

// Why there is no sliding equilibrium, as one line naming the settings responsible.
std::string no_equilibrium_message(const ModelParams& p, NoEquilibrium why, double v);

// The start of a continuous run with run.start = equilibrium: steady sliding at the
// schedule's speed at t = 0, plus the chosen mode at the amplitude that gives the blocks
// (or the pad) a largest speed of run.start_amplitude times that speed.
ChainState equilibrium_start(const ChainForces& forces, const Settings& settings);

}  // namespace bkq
