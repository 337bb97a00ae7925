// Scenes: the parameter table's defaults, reading files and --set overrides, and every
// kind of bad input, checked by the content of the error message (the message is the
// user interface: it must name the key, the value, what is allowed and where).
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "../cli_helpers.hpp"
#include "core/error.hpp"
#include "io/scene.hpp"

namespace bkq {
namespace {

// The message of the bkq::Error thrown by f, or "" when nothing is thrown.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

#define EXPECT_ERROR_HAS(stmt, ...)                                                  \
  do {                                                                               \
    const std::string msg_ = error_of([&] { stmt; });                                \
    ASSERT_FALSE(msg_.empty()) << "expected a bkq::Error from: " #stmt;              \
    for (const std::string& part_ : std::initializer_list<std::string>{__VA_ARGS__}) \
      EXPECT_NE(msg_.find(part_), std::string::npos)                                 \
          << "message '" << msg_ << "' lacks '" << part_ << "'";                     \
    EXPECT_EQ(msg_.find('\n'), std::string::npos) << "not one line: " << msg_;       \
  } while (0)

Scene from(const std::string& text) {
  return Scene::from_text(text, "x.ini");
}

TEST(SceneTable, EveryKeyDeclaredOnceWithDocAndSection) {
  std::set<std::string> keys;
  for (const auto& p : parameter_table()) {
    EXPECT_TRUE(keys.insert(p.key).second) << p.key;
    EXPECT_NE(p.key.find('.'), std::string::npos) << p.key;
    EXPECT_FALSE(p.doc.empty()) << p.key;
    EXPECT_EQ(find_param(p.key), &p);
  }
  for (const char* k :
       {"model.blocks", "model.l", "friction.law", "friction.alpha", "friction.sigma", "drive.mode",
        "drive.speed", "run.events", "run.transient_events", "run.duration", "run.seed",
        "integrator.scheme", "integrator.dt", "output.every", "integrator.tolerance"})
    EXPECT_NE(find_param(k), nullptr) << "contract key missing: " << k;
  EXPECT_EQ(find_param("model.nope"), nullptr);
}

TEST(Scene, Defaults) {
  const Scene s;
  EXPECT_EQ(s.choice("model.kind"), "bk");
  EXPECT_EQ(s.choice("model.parameterisation"), "carlson-langer");
  EXPECT_EQ(s.integer("model.blocks"), 100);
  EXPECT_EQ(s.choice("model.boundary"), "free");
  EXPECT_DOUBLE_EQ(s.real("model.l"), 10);
  EXPECT_DOUBLE_EQ(s.real("model.damping_ratio"), 0.0833333333333333);
  EXPECT_EQ(s.choice("friction.law"), "clst91");
  EXPECT_DOUBLE_EQ(s.real("friction.sigma"), 0.01);
  EXPECT_DOUBLE_EQ(s.real("friction.alpha"), 2.5);
  EXPECT_EQ(s.choice("drive.mode"), "events");
  EXPECT_DOUBLE_EQ(s.real("drive.speed"), 0.01);
  EXPECT_EQ(s.choice("drive.schedule"), "constant");
  EXPECT_EQ(s.integer("run.events"), 100000);
  EXPECT_EQ(s.integer("run.transient_events"), 1000);
  EXPECT_EQ(s.integer("run.seed"), 20261121);
  EXPECT_EQ(s.integer("run.checkpoint_events"), 0);
  EXPECT_EQ(s.choice("integrator.scheme"), "rk4");
  EXPECT_DOUBLE_EQ(s.real("integrator.dt"), 0.01);
  EXPECT_DOUBLE_EQ(s.real("integrator.tolerance"), 1e-8);
  EXPECT_FALSE(s.flag("output.blocks"));
  EXPECT_DOUBLE_EQ(s.real("stats.bin_width"), 0.2);
  EXPECT_FALSE(s.real_or_auto("stats.mu_min").has_value());
  EXPECT_FALSE(s.real_or_auto("stats.mu_max").has_value());
  EXPECT_FALSE(s.is_set("model.blocks"));
  EXPECT_NE(s.origin.find("built-in default"), std::string::npos);
  EXPECT_NO_THROW(s.validate());
}

TEST(Scene, TheBuiltInDefaultChangedBySetSaysWhatItBecame) {
  Scene s;
  EXPECT_EQ(s.provenance(), Scene::kBuiltInOrigin);
  s.set("model.blocks", "40", "values");  // not an override of the command line
  EXPECT_EQ(s.provenance(), Scene::kBuiltInOrigin);
  s.set("model.blocks", "40");
  EXPECT_EQ(s.provenance(), "built-in default with --set overrides (carlson-langer, event-driven)");
  s.set("drive.mode", "continuous");
  EXPECT_EQ(s.provenance(), "built-in default with --set overrides (carlson-langer, continuous)");
  s.set("model.kind", "bkp");
  s.set("model.parameterisation", "thesis");
  EXPECT_EQ(s.provenance(), "built-in default with --set overrides (bkp, thesis, continuous)");
  s.set("model.parameterisation", "si");
  s.set("friction.law", "rsf");
  EXPECT_EQ(s.provenance(), "built-in default with --set overrides (bkp, si, rsf, continuous)");
  // A scene file's origin stays its file's, --set or not.
  Scene f = from("[model]\nblocks = 50\n");
  f.set("drive.mode", "continuous");
  EXPECT_EQ(f.provenance(), "x.ini");
}

TEST(Scene, FileThenOverridesInOrder) {
  Scene s = from(
      "# a comment\n[model]\nblocks = 50\nl = 3\n\n[friction]\nalpha = 1\n"
      "[drive]\nmode = continuous\n[output]\nblocks = yes\n[stats]\nmu_min = -2.5\n");
  EXPECT_EQ(s.origin, "x.ini");
  EXPECT_EQ(s.integer("model.blocks"), 50);
  EXPECT_TRUE(s.is_set("model.blocks"));
  EXPECT_FALSE(s.is_set("model.kind"));
  EXPECT_DOUBLE_EQ(s.real("model.l"), 3);
  EXPECT_TRUE(s.flag("output.blocks"));
  EXPECT_DOUBLE_EQ(*s.real_or_auto("stats.mu_min"), -2.5);
  s.apply_override("model.blocks=7");
  s.apply_override(" model.blocks = 8 ");
  s.apply_override("run.seed=9223372036854775807");
  EXPECT_EQ(s.integer("model.blocks"), 8);
  EXPECT_EQ(s.integer("run.seed"), 9223372036854775807LL);
  EXPECT_NO_THROW(s.validate());
}

TEST(Scene, BooleanSpellings) {
  Scene s;
  for (const char* t : {"true", "yes", "1", "on", "TRUE", "Yes"}) {
    s.set("output.blocks", t);
    EXPECT_TRUE(s.flag("output.blocks")) << t;
  }
  for (const char* f : {"false", "no", "0", "off", "Off"}) {
    s.set("output.blocks", f);
    EXPECT_FALSE(s.flag("output.blocks")) << f;
  }
  EXPECT_ERROR_HAS(s.set("output.blocks", "maybe"), "output.blocks", "'maybe'", "true", "(--set)");
}

TEST(Scene, BadRealsNameKeyValueRangeAndOrigin) {
  EXPECT_ERROR_HAS(Scene::from_text("[friction]\nsigma = 1.5\n", "scenes/x.ini"),
                   "friction.sigma: expected a value in [0, 1), got 1.5 (in scenes/x.ini)");
  Scene s;
  EXPECT_ERROR_HAS(s.set("friction.sigma", "1"), "friction.sigma", "[0, 1)", "got 1");
  EXPECT_NO_THROW(s.set("friction.sigma", "0"));
  EXPECT_ERROR_HAS(s.set("integrator.dt", "0"), "integrator.dt", "(0, 1e+06]", "got 0");
  EXPECT_ERROR_HAS(s.set("integrator.dt", "abc"), "integrator.dt", "'abc'");
  EXPECT_ERROR_HAS(s.set("integrator.dt", "1.0x"), "integrator.dt", "'1.0x'");
  EXPECT_ERROR_HAS(s.set("integrator.dt", ""), "integrator.dt", "''");
  EXPECT_ERROR_HAS(s.set("friction.sigma", "nan"), "friction.sigma", "'nan'");
  EXPECT_ERROR_HAS(s.set("model.l", "inf"), "model.l", "[0, 10000]", "inf");
  EXPECT_ERROR_HAS(s.set("model.pad_mass", "inf"), "model.pad_mass", "got inf");
  EXPECT_ERROR_HAS(s.set("integrator.tolerance", "1e-1"), "integrator.tolerance", "1e-14");
  EXPECT_ERROR_HAS(s.set("stats.mu_min", "low"), "stats.mu_min", "or auto", "'low'");
  EXPECT_NO_THROW(s.set("drive.step_increment", "-0.005"));
  EXPECT_NO_THROW(s.set("model.l", "+1e2"));
  EXPECT_DOUBLE_EQ(s.real("model.l"), 100);
}

TEST(Scene, BadIntegers) {
  Scene s;
  EXPECT_ERROR_HAS(s.set("model.blocks", "12abc"),
                   "model.blocks: expected an integer in [1, 10000000], got '12abc' (--set)");
  EXPECT_ERROR_HAS(s.set("model.blocks", "1.5"), "model.blocks", "'1.5'");
  EXPECT_ERROR_HAS(s.set("model.blocks", "0"), "model.blocks", "[1, 10000000]", "got 0");
  EXPECT_ERROR_HAS(s.set("model.blocks", "-3"), "model.blocks", "got -3");
  EXPECT_ERROR_HAS(s.set("run.seed", "99999999999999999999"), "run.seed",
                   "[0, 9223372036854775807]", "99999999999999999999");
  EXPECT_ERROR_HAS(s.set("run.events", "1e6"), "run.events", "'1e6'");
}

TEST(Scene, BadChoice) {
  EXPECT_ERROR_HAS(
      from("[friction]\nlaw = coulomb\n"),
      "friction.law: expected one of thesis|clst91|cl89|none|table|rsf, got 'coulomb' (in x.ini)");
  Scene s;
  EXPECT_ERROR_HAS(s.set("integrator.scheme", "euler"), "rk2|rk4|verlet|theta|adaptive", "'euler'");
}

TEST(Scene, UnknownKeysSuggestTheNearest) {
  EXPECT_ERROR_HAS(from("[friction]\nsigmaa = 0.1\n"),
                   "unknown key 'friction.sigmaa' (in x.ini); did you mean 'friction.sigma'?");
  EXPECT_ERROR_HAS(from("[modle]\nblocks = 3\n"), "'modle.blocks'", "did you mean 'model.blocks'?");
  EXPECT_ERROR_HAS(from("blocks = 3\n"), "unknown key 'blocks'");
  Scene s;
  EXPECT_ERROR_HAS(s.apply_override("run.event=5"), "unknown key 'run.event' (--set)",
                   "did you mean 'run.events'?");
  EXPECT_ERROR_HAS(s.apply_override("completely.unrelated.thing=1"), "unknown key",
                   "--dump-defaults");
}

TEST(Scene, MalformedInput) {
  Scene s;
  EXPECT_ERROR_HAS(s.apply_override("model.blocks"), "--set", "section.key=value",
                   "'model.blocks'");
  EXPECT_ERROR_HAS(s.apply_override("=5"), "--set", "'=5'");
  EXPECT_ERROR_HAS(from("[model]\nblocks = 5\nblocks = 6\n"), "model.blocks", "more than once",
                   "x.ini");
  EXPECT_ERROR_HAS(from("[model]\nthis line has no equals sign\n"), "x.ini");
}

TEST(Scene, MissingFile) {
  EXPECT_ERROR_HAS(Scene::from_file("nope.ini"),
                   "cannot read scene file 'nope.ini': No such file or directory");
  test::TempDir dir;
  EXPECT_ERROR_HAS(Scene::from_file(dir.path().string()), "cannot read scene file",
                   "Is a directory");
}

TEST(Scene, FromFile) {
  test::TempDir dir;
  const std::string path = dir.write("a.ini", "[run]\nevents = 12\n");
  const Scene s = Scene::from_file(path);
  EXPECT_EQ(s.integer("run.events"), 12);
  EXPECT_EQ(s.origin, path);
  EXPECT_ERROR_HAS(Scene::from_file(dir.write("b.ini", "[run]\nevents = x\n")), "run.events", "'x'",
                   "(in " + dir.file("b.ini") + ")");
}

TEST(SceneValidate, ParameterisationOnlyKeys) {
  EXPECT_ERROR_HAS(from("[model]\npad_mass = 5\n").validate(), "model.pad_mass",
                   "model.parameterisation", "carlson-langer", "x.ini");
  EXPECT_ERROR_HAS(from("[friction]\nF0 = 2\n").validate(), "friction.F0",
                   "model.parameterisation");
  EXPECT_ERROR_HAS(from("[model]\nparameterisation = thesis\nl = 3\n").validate(), "model.l",
                   "model.parameterisation = thesis");
  EXPECT_ERROR_HAS(from("[model]\nparameterisation = thesis\n[friction]\nalpha = 1\n").validate(),
                   "friction.alpha", "model.parameterisation");
  EXPECT_NO_THROW(from("[model]\nparameterisation = thesis\npad_mass = 5\ns_c = 0.1\n"
                       "[friction]\nF0 = 2\nvc = 3\n")
                      .validate());
}

TEST(SceneValidate, ScheduleOnlyKeys) {
  const std::string c = "[drive]\nmode = continuous\n";
  EXPECT_ERROR_HAS(from(c + "step_interval = 10\n").validate(), "drive.step_interval",
                   "drive.schedule = steps", "drive.schedule = constant");
  EXPECT_ERROR_HAS(from(c + "schedule = steps\nramp_to = 2\n").validate(), "drive.ramp_to",
                   "drive.schedule");
  EXPECT_NO_THROW(from(c + "schedule = ramp\nramp_to = 0\nramp_from = 1\n").validate());
  EXPECT_NO_THROW(from(c + "schedule = steps\nstep_interval = 10\n").validate());
}

TEST(SceneValidate, KindModeAndSchemeOnlyKeys) {
  // Keys of another model kind, drive mode or scheme are refused, not silently ignored.
  EXPECT_ERROR_HAS(from("[model]\ndamping_ratio = 0.2\n").validate(), "model.damping_ratio",
                   "model.kind = bkp|1dof", "model.kind = bk");
  EXPECT_NO_THROW(from("[model]\nkind = bkp\ndamping_ratio = 0.2\n").validate());
  EXPECT_NO_THROW(from("[model]\nkind = 1dof\ndamping_ratio = 0.2\n").validate());
  EXPECT_ERROR_HAS(from("[model]\ns_m = 2\n").validate(), "model.s_m",
                   "model.parameterisation = thesis or model.kind = bkp",
                   "model.parameterisation = carlson-langer and model.kind = bk");
  EXPECT_NO_THROW(from("[model]\nkind = bkp\ns_p = 2\n").validate());
  EXPECT_ERROR_HAS(from("[drive]\nmode = continuous\n[run]\nevents = 5\n").validate(), "run.events",
                   "drive.mode = events");
  EXPECT_ERROR_HAS(from("[run]\nduration = 5\n").validate(), "run.duration",
                   "drive.mode = continuous");
  EXPECT_ERROR_HAS(from("[integrator]\ntolerance = 1e-6\n").validate(), "integrator.tolerance",
                   "integrator.scheme = adaptive");
}

TEST(SceneValidate, FileKeysThatDoNotApplyAreDroppedWithAWarningSetKeysAreRefused) {
  Scene s = from(
      "[model]\ndamping_ratio = 0.2\n[drive]\nmode = events\nschedule = steps\n"
      "step_interval = 10\n");
  const auto warnings = s.drop_inapplicable();
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_NE(warnings[0].find("model.damping_ratio = 0.2 (in x.ini) does not apply"),
            std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[0].find("needs model.kind = bkp|1dof, but model.kind = bk; ignored"),
            std::string::npos)
      << warnings[0];
  // The schedule goes first, so the step keys are judged against the default schedule.
  EXPECT_NE(warnings[2].find("drive.step_interval"), std::string::npos) << warnings[2];
  EXPECT_NO_THROW(s.validate());
  EXPECT_EQ(s, Scene()) << "ignored keys hold their defaults";
  EXPECT_FALSE(s.is_set("model.damping_ratio"));

  Scene t;
  t.apply_override("run.duration=5");
  EXPECT_ERROR_HAS(t.drop_inapplicable(), "--set run.duration=5 does not apply",
                   "drive.mode = continuous");
  // A --set of the controller makes the file's key apply.
  Scene u = from("[model]\ndamping_ratio = 0.2\n");
  u.apply_override("model.kind=bkp");
  EXPECT_TRUE(u.drop_inapplicable().empty());
  EXPECT_DOUBLE_EQ(u.real("model.damping_ratio"), 0.2);
}

TEST(SceneIni, KeysThatDoNotApplyAreWrittenAsCommentsAndReadBack) {
  Scene s = from("[model]\nkind = bkp\ndamping_ratio = 0.2\n");
  s.apply_override("model.kind=bk");
  ASSERT_EQ(s.drop_inapplicable().size(), 1u);
  const std::string ini = s.to_ini();
  EXPECT_NE(ini.find("# damping_ratio = 0.0833333333333333  (unused: needs model.kind = "
                     "bkp|1dof, but model.kind = bk)"),
            std::string::npos)
      << ini;
  EXPECT_NE(ini.find("\nevents = 100000\n"), std::string::npos) << "events applies: " << ini;
  EXPECT_NE(ini.find("# duration = 1000  (unused: needs drive.mode = continuous"),
            std::string::npos);
  Scene back = Scene::from_text(ini, "scene.ini");
  EXPECT_TRUE(back.drop_inapplicable().empty());
  EXPECT_NO_THROW(back.validate());
  EXPECT_EQ(back, s);
}

TEST(SceneValidate, OneDofBoundaryFitWindowAndEventsWithAnyScheme) {
  EXPECT_ERROR_HAS(from("[model]\nkind = 1dof\nblocks = 5\n").validate(), "model.blocks",
                   "model.kind = 1dof");
  EXPECT_NO_THROW(from("[model]\nkind = 1dof\nblocks = 1\n").validate());
  EXPECT_NO_THROW(from("[model]\nkind = 1dof\n").validate());
  EXPECT_ERROR_HAS(from("[model]\nboundary = periodic\nblocks = 2\n").validate(), "periodic",
                   "model.blocks");
  EXPECT_NO_THROW(from("[model]\nboundary = periodic\nblocks = 3\n").validate());
  EXPECT_ERROR_HAS(from("[stats]\nmu_min = 2\nmu_max = 2\n").validate(), "stats.mu_min",
                   "stats.mu_max");
  EXPECT_NO_THROW(from("[stats]\nmu_min = 2\nmu_max = auto\n").validate());
  EXPECT_NO_THROW(from("[drive]\nmode = events\n[integrator]\nscheme = theta\n").validate());
  EXPECT_NO_THROW(from("[integrator]\nscheme = adaptive\n").validate());
}

TEST(SceneIni, DumpDefaultsReadsBackToDefaults) {
  const std::string text = dump_defaults();
  const Scene back = Scene::from_text(text, "dump");
  EXPECT_EQ(back, Scene());
  EXPECT_NO_THROW(back.validate());
  EXPECT_EQ(back.hash(), Scene().hash());
  // Every key is documented in the dump, with its range.
  for (const auto& p : parameter_table()) {
    const std::string name = p.key.substr(p.key.find('.') + 1);
    EXPECT_NE(text.find(p.doc), std::string::npos) << p.key;
    EXPECT_NE(text.find(name + " = "), std::string::npos) << p.key;
  }
  EXPECT_NE(text.find("(allowed: [0, 1))"), std::string::npos);
}

TEST(SceneIni, RoundTripOfAnEditedScene) {
  Scene s = from(
      "[model]\nkind = bkp\nparameterisation = thesis\npad_mass = 50\n"
      "[drive]\nmode = continuous\nschedule = ramp\nramp_to = 0.5\n"
      "[stats]\nmu_max = 4.25\n[output]\nblocks = on\n");
  s.apply_override("model.damping_ratio=0.1");
  s.apply_override("run.seed=42");
  const std::string ini = s.to_ini({"provenance line"});
  EXPECT_EQ(ini.rfind("# provenance line\n", 0), 0u);
  const Scene back = Scene::from_text(ini, "scene.ini");
  EXPECT_EQ(back, s);
  EXPECT_EQ(back.hash(), s.hash());
  EXPECT_NO_THROW(back.validate());
  EXPECT_EQ(back.to_ini(), s.to_ini());
}

TEST(SceneIni, HashSeesEveryValue) {
  Scene a, b;
  EXPECT_EQ(a.hash(), b.hash());
  b.set("run.seed", "1");
  EXPECT_NE(a.hash(), b.hash());
  // Same value, different spelling: same hash (values are normalised).
  Scene c;
  c.set("model.l", "10.0");
  c.set("output.blocks", "no");
  EXPECT_EQ(a.hash(), c.hash());
}

TEST(SceneShipped, BothShippedScenesLoadAndValidate) {
  const std::string dir = std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/";
  const Scene cl = Scene::from_file(dir + "carlson-langer.ini");
  EXPECT_NO_THROW(cl.validate());
  EXPECT_EQ(cl.choice("drive.mode"), "events");
  EXPECT_EQ(cl.choice("friction.law"), "clst91");
  EXPECT_DOUBLE_EQ(cl.real("model.l"), 10);
  EXPECT_DOUBLE_EQ(cl.real("friction.alpha"), 2.5);
  EXPECT_EQ(cl.integer("model.blocks"), 100);

  const Scene th = Scene::from_file(dir + "thesis.ini");
  EXPECT_NO_THROW(th.validate());
  EXPECT_EQ(th.choice("model.parameterisation"), "thesis");
  EXPECT_EQ(th.choice("model.kind"), "bkp");
  EXPECT_EQ(th.choice("drive.mode"), "continuous");
  EXPECT_EQ(th.choice("drive.schedule"), "steps");
  EXPECT_DOUBLE_EQ(th.real("integrator.dt"), 0.005);
  EXPECT_DOUBLE_EQ(th.real("model.s_c"), 0.01);
}

}  // namespace
}  // namespace bkq
