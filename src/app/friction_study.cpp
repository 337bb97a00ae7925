// The friction study; see friction_study.hpp.
#include "app/friction_study.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <thread>

#include "app/run.hpp"
#include "app/special_law.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "io/output.hpp"
#include "io/scene.hpp"
#include "io/scene_keys.hpp"
#include "io/segments_csv.hpp"
#include "io/settings.hpp"

namespace bkq {

namespace fs = std::filesystem;

const std::vector<StudyRun>& study_grid() {
  static const std::vector<StudyRun> grid = {
      {0.005, 0.005, 15}, {0.08, 0.01, 13}, {0.22, 0.02, 10}, {0.45, 0.05, 9}, {0.86, 0.01, 15}};
  return grid;
}

namespace {

struct Job {
  std::string config;
  std::uint64_t seed;
  int run;
  std::string dir;
  Scene scene;
};

// The scene of `config` set up for grid run `r` at `seed`.
Scene job_scene(const std::string& file, const StudyRun& r, std::uint64_t seed, double segment) {
  Scene scene = Scene::from_file(file);
  scene.set(key::drive_schedule, "steps");
  scene.set(key::drive_speed, format_real(r.v0));
  scene.set(key::drive_step_increment, format_real(r.inc));
  scene.set(key::drive_step_interval, format_real(segment));
  scene.set(key::run_duration, format_real(segment * r.count));
  scene.set(key::run_seed, std::to_string(seed));
  // The study reads segments.csv only; keep the time series small.
  scene.set(key::output_every, format_real(segment / 100));
  scene.set(key::output_blocks, "false");
  scene.validate();
  return scene;
}

// Runs `jobs` on `threads` threads, a progress line on stderr per finished run.
void run_all(std::vector<Job>& jobs, int threads, bool quiet,
             std::chrono::steady_clock::time_point t0, int& done_total, int total) {
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::string failure;
  auto worker = [&] {
    for (;;) {
      const std::size_t k = next++;
      if (k >= jobs.size()) return;
      Job& job = jobs[k];
      const auto start = std::chrono::steady_clock::now();
      try {
        RunRequest req;
        req.scene = job.scene;
        req.out_dir = job.dir;
        req.force = true;
        req.quiet = true;
        run_scene(req);
      } catch (const std::exception& e) {
        std::lock_guard lock(mutex);
        if (failure.empty()) failure = job.dir + ": " + e.what();
        return;
      }
      const auto now = std::chrono::steady_clock::now();
      std::lock_guard lock(mutex);
      ++done_total;
      if (!quiet)
        std::fprintf(
            stderr, "friction-study: [%d/%d] %s seed %llu run %d: %.1f s (elapsed %.0f s)\n",
            done_total, total, job.config.c_str(), static_cast<unsigned long long>(job.seed),
            job.run, std::chrono::duration<double>(now - start).count(),
            std::chrono::duration<double>(now - t0).count());
    }
  };
  std::vector<std::thread> pool;
  for (int i = 0; i < std::max(threads, 1); ++i) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  if (!failure.empty()) throw Error("friction-study: " + failure);
}

}  // namespace

std::string run_friction_study(const StudyRequest& req) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!(req.segment > 0)) throw Error("friction-study: --segment must be > 0");
  const auto& grid = study_grid();
  auto scene_file = [&](const std::string& c) {
    return (fs::path(req.scenes_dir) / (c + ".ini")).string();
  };
  bool want_special = false;
  std::vector<Job> first, second;
  for (const auto& c : req.configs) {
    if (c == "special-1dof") {
      want_special = true;
      continue;
    }
    if (!fs::exists(scene_file(c)))
      throw Error("friction-study: no scene " + scene_file(c) + " for configuration " + c);
    const Scene base = Scene::from_file(scene_file(c));
    const std::uint64_t seed0 = scene_values(base).run.seed;
    const int seeds = (c == "bkp" || c == "bk") ? req.seeds : 1;
    for (int s = 0; s < seeds; ++s)
      for (std::size_t r = 0; r < grid.size(); ++r) {
        const std::uint64_t seed = seed0 + static_cast<std::uint64_t>(s);
        const std::string dir =
            (fs::path(req.out) / c / ("seed" + std::to_string(seed)) / ("run" + std::to_string(r)))
                .string();
        first.push_back({c, seed, static_cast<int>(r), dir,
                         job_scene(scene_file(c), grid[r], seed, req.segment)});
      }
  }
  // The special 1DOF needs the tabulated law (friction.law = table) and BK runs to build it.
  const bool special_possible =
      find_param(key::friction_table) != nullptr && fs::exists(scene_file("special-1dof")) &&
      std::find(req.configs.begin(), req.configs.end(), "bk") != req.configs.end();
  if (want_special && !special_possible && !req.quiet)
    std::fprintf(stderr,
                 "friction-study: special-1dof skipped: it needs the bk configuration, %s and "
                 "friction.law = table\n",
                 scene_file("special-1dof").c_str());
  // The scenes are read and checked above, before the folder is made. The folder rule of
  // every command that writes a folder: a new or empty folder (the runs' subfolders do not
  // count), or force; its lock while the study runs.
  const OutputFolder folder(req.out, req.force, false, "friction-study");
  const int total = static_cast<int>(first.size()) +
                    (want_special && special_possible ? static_cast<int>(grid.size()) : 0);
  int done = 0;
  run_all(first, req.jobs, req.quiet, t0, done, total);

  if (want_special && special_possible) {
    // The law from the first seed's BK runs.
    std::vector<std::string> seed0_dirs;
    const std::uint64_t bk_seed0 = [&] {
      for (const Job& j : first)
        if (j.config == "bk") return j.seed;
      return std::uint64_t{0};
    }();
    for (const Job& j : first)
      if (j.config == "bk" && j.seed == bk_seed0) seed0_dirs.push_back(j.dir);
    const std::string law = (fs::path(req.out) / "special_law.csv").string();
    std::vector<std::string> comments = {"special-law of the friction study, from:"};
    for (const auto& d : seed0_dirs) comments.push_back("  " + d);
    write_file_atomic(law, special_law_csv(special_law(seed0_dirs), comments));
    const std::string file = scene_file("special-1dof");
    const Scene base = Scene::from_file(file);
    const std::uint64_t seed = scene_values(base).run.seed;
    for (std::size_t r = 0; r < grid.size(); ++r) {
      Scene scene = job_scene(file, grid[r], seed, req.segment);
      scene.set(key::friction_table, fs::absolute(law).string());
      scene.validate();
      second.push_back({"special-1dof", seed, static_cast<int>(r),
                        (fs::path(req.out) / "special-1dof" / ("seed" + std::to_string(seed)) /
                         ("run" + std::to_string(r)))
                            .string(),
                        scene});
    }
    run_all(second, req.jobs, req.quiet, t0, done, total);
  }

  // Gather the segments into friction_study.csv.
  std::string csv = header_of(friction_study_schema()) + "\n";
  const ModelParams law_params = model_from_scene(Scene::from_file(scene_file("bkp")));
  for (const auto* jobs : {&first, &second})
    for (const Job& j : *jobs) {
      const ModelParams p = model_from_scene(j.scene);
      const double m_x = p.pad_moves() ? p.m_x : 0.0;
      for (const SegmentRow& r : read_segments_csv(fs::path(j.dir) / "segments.csv")) {
        const SegmentStat& f = r.stats[0];
        const SegmentStat& x = r.stats[1];
        const ModelParams& q = law_params;
        const double phi = q.F0 * (1 - q.sigma) / (1 + std::abs(r.speed) / ((1 - q.sigma) * q.v_c));
        csv += j.config;
        csv += ',';
        csv += std::to_string(j.seed);
        csv += ',';
        csv += std::to_string(j.run);
        for (double v : {r.speed, f.mean, f.mean_err, f.amp, f.amp_err, x.amp * m_x,
                         x.amp_err * m_x, q.n * q.m_u * phi}) {
          csv += ',';
          csv += format_real(v);
        }
        csv += "\n";
      }
    }
  const std::string path = (fs::path(req.out) / "friction_study.csv").string();
  write_file_atomic(path, csv);
  if (!req.quiet)
    std::fprintf(stderr, "friction-study: %d runs in %.0f s; wrote %s\n", done,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                 path.c_str());
  return path;
}

}  // namespace bkq
