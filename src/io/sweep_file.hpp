// Sweep files: a base scene, the scene keys to vary and how, replicas per point and what
// each replica keeps, read with the one INI parser (io/ini.hpp) and every value checked
// against the one parameter table (io/scene.hpp), so any declared key can be swept and a
// bad value is refused before anything runs. Also the columns of sweep.csv, declared once.
//
//   [sweep]
//   scene = ../scenes/carlson-langer.ini   # relative to the sweep file; omitted: built-in
//   combine = product                      # product | zip
//   replicas = 2                           # runs per point, seeds base + point*R + replica
//   collect = catalog, histogram           # per-replica files kept (summary always)
//   [vary]
//   friction.alpha = 1, 2, 2.5, 3          # a list
//   drive.speed = 0.005:1:200              # lo:hi:count, both ends included
//   drive.speed = log:0.005:1:50           # log-spaced
//   [set]
//   run.events = 100000                    # overrides of the base scene for every point
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "io/scene.hpp"
#include "io/schema.hpp"

namespace bkq {

enum class SweepCombine { Product, Zip };

struct SweptKey {
  std::string key;                  // "section.key", declared in parameter_table()
  std::vector<std::string> values;  // normalised text, as the scene stores it
};

// One point: the base scene with each swept key set to one of its values.
struct SweepPoint {
  std::vector<std::pair<std::string, std::string>> values;  // in the order of SweepSpec::keys
  Scene scene;
};

// At most this many points per sweep (each is a folder of runs) and this many tasks (points x
// replicas, each a run folder): beyond them a sweep is refused with the number it would have.
inline constexpr std::size_t kMaxSweepPoints = 100000;
inline constexpr std::size_t kMaxSweepTasks = 1000000;

struct SweepSpec {
  std::string origin;  // the sweep file
  Scene base;          // base scene file + [set] + command-line overrides
  std::vector<SweptKey> keys;
  SweepCombine combine = SweepCombine::Product;
  int replicas = 1;
  bool keep_catalog = true;    // collect: catalog
  bool keep_histogram = true;  // collect: histogram
  std::string text;            // the sweep file as read (written beside sweep.csv)

  // The number of points: the product of the lists' lengths, or their common length under
  // zip. bkq::Error naming the number when it (or points x replicas) exceeds the bounds
  // below, checked before anything is planned, so the product of several long lists cannot
  // overflow or fill memory.
  std::size_t point_count() const;
  // Point i (0 <= i < point_count()), made on demand: the plan holds no scene per point, so
  // its memory does not grow with the number of points. Product: the last key varies fastest.
  SweepPoint point(std::size_t i) const;
  // Only its swept values, without building the scene.
  std::vector<std::pair<std::string, std::string>> point_values(std::size_t i) const;
  // Every point in order (point(0), point(1), ...); for small sweeps and tests.
  std::vector<SweepPoint> points() const;
};

// Parses a sweep file. `overrides` are `section.key=value` assignments applied to the base
// scene after its file and the [set] section (the --set options of `bkquake sweep`).
// Errors (unknown section or key, a value outside the key's range, an empty list, lists of
// different lengths under zip, a key both set and varied) throw bkq::Error naming the key.
SweepSpec read_sweep_file(const std::string& path, const std::vector<std::string>& overrides);
SweepSpec parse_sweep(const std::string& text, const std::string& origin,
                      const std::string& base_dir, const std::vector<std::string>& overrides);

// Expands one [vary] value: "a, b, c", "lo:hi:count" or "log:lo:hi:count" into texts
// (reals printed shortest round-trip). Errors name `key`.
std::vector<std::string> expand_sweep_values(const std::string& key, const std::string& text);

// sweep.csv: `point`, then one column per swept key (named by the key), then these.
const Schema& sweep_csv_schema();
// sweep_fit.csv, written by `bkquake fit SWEEP_DIR` beside sweep.csv: one row per point
// refitted from its merged histogram.csv (the swept keys after `point`, as in sweep.csv).
const Schema& sweep_fit_schema();
namespace sweep_col {
inline constexpr const char* point = "point";
}

}  // namespace bkq
