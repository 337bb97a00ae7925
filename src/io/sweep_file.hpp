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

struct SweepSpec {
  std::string origin;  // the sweep file
  Scene base;          // base scene file + [set] + command-line overrides
  std::vector<SweptKey> keys;
  SweepCombine combine = SweepCombine::Product;
  int replicas = 1;
  bool keep_catalog = true;    // collect: catalog
  bool keep_histogram = true;  // collect: histogram
  std::string text;            // the sweep file as read (written beside sweep.csv)

  // The points in order: product with the last key varying fastest, or zip.
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
