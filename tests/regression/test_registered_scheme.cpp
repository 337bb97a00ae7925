// A scheme the program does not ship, registered at run time (register_scheme), is a scene's
// choice as a shipped one is: a scene naming it validates, runs through `bkquake run`'s
// run_scene and writes a scene.ini that reads back; its traits decide where located
// transitions and the general kernels apply; `bkquake accuracy` offers it. The reference docs
// still list the shipped schemes. Unregistered, it is refused with the one-line message of
// any value a key does not allow, also by a scene read while it was registered.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "../cli_helpers.hpp"
#include "app/accuracy.hpp"
#include "app/run.hpp"
#include "core/error.hpp"
#include "integrate/rk2.hpp"
#include "integrate/scheme_traits.hpp"
#include "integrate/stencil_kernel.hpp"  // run_stencil<TwinMethod>, for the lattice case
#include "io/readme_tables.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"

namespace bkq {
namespace {

// rk2's method under a name of its own: a new explicit scheme is a Method and a registration
// (integrate/explicit_scheme.hpp). Being rk2 step for step, its runs must be rk2's bit for bit.
struct TwinMethod : Rk2Method {
  static constexpr const char* name = "test-twin";
};
using Twin = ExplicitScheme<TwinMethod>;

struct Registered {
  Registered() {
    register_scheme("test-twin", Twin::kTraits, [](int n, double) -> std::unique_ptr<Stepper> {
      return std::make_unique<Twin>(n);
    });
  }
  ~Registered() { unregister_scheme("test-twin"); }
  Registered(const Registered&) = delete;
  Registered& operator=(const Registered&) = delete;
};

using Keys = std::vector<std::pair<std::string, std::string>>;

Scene scene_of(const Keys& keys) {
  Scene s;
  for (const auto& [k, v] : keys) s.set(k, v);
  s.drop_inapplicable();
  s.validate();
  return s;
}

Keys chain(const std::string& scheme, const std::string& transitions) {
  return {{"model.blocks", "30"},         {"run.events", "300"},
          {"run.transient_events", "50"}, {"integrator.dt", "0.005"},
          {"integrator.scheme", scheme},  {"integrator.transitions", transitions}};
}

// Runs the scene as `bkquake run` does; returns the folder's catalog.csv.
std::string run_catalog(const Scene& scene, const std::string& out) {
  RunRequest req;
  req.scene = scene;
  req.out_dir = out;
  req.quiet = true;
  EXPECT_EQ(run_scene(req), 0) << out;
  return test::read_file(out + "/catalog.csv");
}

std::string shipped_list() {
  std::string t;
  for (const std::string& k : shipped_scheme_keywords()) t += (t.empty() ? "" : "|") + k;
  return t;
}

TEST(RegisteredScheme, ASceneNamingItValidatesAndRunsWithItsTraits) {
  test::TempDir dir;
  const Registered guard;
  for (const char* transitions : {"step", "located"}) {
    SCOPED_TRACE(transitions);
    // Located transitions apply to it because its traits say it is locatable.
    const Scene twin = scene_of(chain("test-twin", transitions));
    EXPECT_TRUE(twin.applies("integrator.transitions"));
    const std::string out = dir.file(std::string("twin-") + transitions);
    const std::string catalog = run_catalog(twin, out);
    EXPECT_GT(std::count(catalog.begin(), catalog.end(), '\n'), 300);
    EXPECT_EQ(catalog, run_catalog(scene_of(chain("rk2", transitions)),
                                   dir.file(std::string("rk2-") + transitions)));
    // Its scene.ini names it and reads back to the same scene.
    const std::string ini = test::read_file(out + "/scene.ini");
    EXPECT_NE(ini.find("\nscheme = test-twin\n"), std::string::npos);
    EXPECT_TRUE(Scene::from_file(out + "/scene.ini") == twin);
  }
  // It declares the general kernels: a lattice takes it, while the registry's list of the
  // schemes that do names it beside the shipped ones.
  const Keys lattice = {{"model.rows", "4"}, {"model.blocks", "8"}, {"drive.mode", "continuous"}};
  Keys with_twin = lattice, with_theta = lattice;
  with_twin.emplace_back("integrator.scheme", "test-twin");
  with_theta.emplace_back("integrator.scheme", "theta");
  EXPECT_NO_THROW(settings_from_scene(scene_of(with_twin)));
  try {
    settings_from_scene(scene_of(with_theta));
    ADD_FAILURE() << "theta accepted on a lattice";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "allowed here: integrator.scheme = rk2, rk4, verlet or test-twin with "
                  "integrator.transitions = step"),
              std::string::npos)
        << e.what();
  }
  // bkquake accuracy offers it; the reference docs list the shipped schemes only.
  const std::vector<std::string> offered = AccuracyOptions().schemes;
  EXPECT_NE(std::find(offered.begin(), offered.end(), "test-twin"), offered.end());
  const ParamSpec& scheme = *find_param("integrator.scheme");
  EXPECT_EQ(allowed_text(scheme), shipped_list() + "|test-twin");
  EXPECT_EQ(documented_allowed_text(scheme), shipped_list());
  for (const ReadmeTable& t : readme_tables())
    EXPECT_EQ(t.markdown.find("test-twin"), std::string::npos) << t.name;
}

TEST(RegisteredScheme, UnregisteredItIsRefusedWithTheUsualMessage) {
  test::TempDir dir;
  Scene read_while_registered;
  {
    const Registered guard;
    read_while_registered = scene_of(chain("test-twin", "step"));
    dir.write("twin.ini", "[integrator]\nscheme = test-twin\n");
  }
  const std::string expected =
      "integrator.scheme: expected one of " + shipped_list() + ", got 'test-twin'";
  try {
    Scene s;
    s.set("integrator.scheme", "test-twin");
    ADD_FAILURE() << "--set integrator.scheme=test-twin accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), expected + " (--set)");
  }
  try {
    Scene::from_file(dir.file("twin.ini"));
    ADD_FAILURE() << "a scene file naming test-twin accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), expected + " (in " + dir.file("twin.ini") + ")");
  }
  try {
    read_while_registered.validate();
    ADD_FAILURE() << "a scene read while test-twin was registered validated without it";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), expected + " (built-in default scene with --set overrides)");
  }
  const std::vector<std::string> offered = AccuracyOptions().schemes;
  EXPECT_EQ(std::find(offered.begin(), offered.end(), "test-twin"), offered.end());
}

}  // namespace
}  // namespace bkq
