// The scene keys' declarations (io/scene_table.cpp): each row fills its own member of
// SceneValues and writes it back to the same text, for every key of every shipped scene and
// of --dump-defaults; and each row's applies-when rule refuses the key in every context the
// row excludes, found by walking the rows and the values of their controllers.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/scene.hpp"
#include "io/scene_values.hpp"

namespace fs = std::filesystem;
using namespace bkq;

namespace {

const fs::path kSource = BKQUAKE_SOURCE_DIR;

// Every shipped scene, as a run reads it (keys that do not apply dropped), and the built-in
// default that --dump-defaults prints.
std::vector<Scene> shipped_scenes() {
  std::vector<Scene> scenes{Scene()};
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(kSource / "data" / "scenes"))
    if (e.path().extension() == ".ini") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    Scene s = Scene::from_file(f.string());
    s.drop_inapplicable();
    scenes.push_back(s);
  }
  return scenes;
}

// A scene holding, for every key, the text its row writes from `v`.
Scene scene_of(const SceneValues& v) {
  Scene s;
  for (const ParamSpec& p : parameter_table()) s.set(p.key, p.text_of(v), "values");
  return s;
}

// Values a key can take other than its present one, normalised as the scene stores them.
std::vector<std::string> other_values(const Scene& scene, const ParamSpec& p) {
  std::vector<std::string> candidates;
  switch (p.type) {
    case ParamType::Choice:
      candidates = p.choices;
      break;
    case ParamType::Boolean:
      candidates = {"true", "false"};
      break;
    case ParamType::Path:
      candidates = {"/nonexistent/table.csv"};
      break;
    case ParamType::Integer:
    case ParamType::Real:
      candidates = {"0", "1", "3", "7", "0.3", "0.6", "-2", "1e-6", "1e-3"};
      if (p.allow_auto) candidates.push_back(p.keyword);
      break;
  }
  std::vector<std::string> out;
  for (const std::string& c : candidates) {
    Scene s;
    try {
      s.set(p.key, c, "test");
    } catch (const Error&) {
      continue;  // outside the key's range
    }
    if (s.text(p.key) != scene.text(p.key)) out.push_back(s.text(p.key));
  }
  return out;
}

}  // namespace

TEST(SceneDeclarations, EveryKeyOfEveryShippedSceneRoundTripsThroughItsMember) {
  std::vector<Scene> scenes = shipped_scenes();
  // --dump-defaults read back, and each scene's own effective scene.ini read back.
  scenes.push_back(Scene::from_text(dump_defaults(), "--dump-defaults"));
  const std::size_t shipped = scenes.size();
  for (std::size_t i = 1; i < shipped; ++i)
    scenes.push_back(Scene::from_text(scenes[i].to_ini(), scenes[i].origin + " scene.ini"));
  ASSERT_GT(scenes.size(), 20u);
  for (const Scene& scene : scenes) {
    const SceneValues v = scene_values(scene);
    for (const ParamSpec& p : parameter_table())
      EXPECT_EQ(p.text_of(v), scene.text(p.key)) << p.key << " in " << scene.origin;
    const Scene back = scene_of(v);
    EXPECT_TRUE(back == scene) << scene.origin;
    EXPECT_EQ(back.to_ini(), scene.to_ini()) << scene.origin;
    EXPECT_EQ(back.hash(), scene.hash()) << scene.origin;
  }
}

TEST(SceneDeclarations, EachRowFillsAMemberNoOtherRowReads) {
  // Two rows bound to one member, or a row whose member does not hold what it was given,
  // show up as a change that does not come back, or that comes back through another key.
  for (const Scene& scene : shipped_scenes()) {
    const SceneValues v = scene_values(scene);
    for (const ParamSpec& p : parameter_table()) {
      const std::vector<std::string> others = other_values(scene, p);
      EXPECT_FALSE(others.empty()) << p.key << " has no other value to try";
      for (const std::string& value : others) {
        SceneValues changed = v;
        p.fill(changed, value);
        EXPECT_EQ(p.text_of(changed), value) << p.key;
        for (const ParamSpec& q : parameter_table()) {
          if (q.key == p.key) continue;
          EXPECT_EQ(q.text_of(changed), q.text_of(v))
              << "filling " << p.key << " = " << value << " changed " << q.key;
        }
      }
    }
  }
}

TEST(SceneDeclarations, AKeyIsRefusedInEveryContextItsRowExcludes) {
  // For each row, each of its applies-when rules, each condition of the rule and each value
  // of that condition's controller the condition leaves out: a shipped scene in which the
  // controller applies, with the controller set to that value, is a context the row
  // excludes (when no other condition of the rule holds there). The key must not apply
  // there, say why, be refused when given by --set, and be written as a comment.
  const std::vector<Scene> bases = shipped_scenes();
  std::set<std::string> untried;
  int contexts = 0;
  for (const ParamSpec& p : parameter_table()) {
    for (const Requirement& rule : p.applies_when) {
      for (const KeyCondition& c : rule.any_of) {
        const ParamSpec& controller = *find_param(c.controller);
        const std::vector<std::string> all = controller.type == ParamType::Boolean
                                                 ? std::vector<std::string>{"true", "false"}
                                                 : controller.allowed_choices();
        const std::vector<std::string> values = c.allowed();
        for (const std::string& excluded : all) {
          if (std::find(values.begin(), values.end(), excluded) != values.end()) continue;
          bool tried = false;
          for (const Scene& base : bases) {
            if (!base.applies(c.controller)) continue;
            Scene s = base;
            s.set(c.controller, excluded, "context");
            bool other_holds = false;
            for (const KeyCondition& d : rule.any_of) {
              const std::vector<std::string> dv = d.allowed();
              other_holds =
                  other_holds || std::find(dv.begin(), dv.end(), s.text(d.controller)) != dv.end();
            }
            if (other_holds) continue;
            tried = true;
            ++contexts;
            const std::string context =
                c.controller + " = " + excluded + " in " + base.origin + " for " + p.key;
            EXPECT_FALSE(s.applies(p.key)) << context;
            EXPECT_NE(s.why_not(p.key).find("needs"), std::string::npos) << context;
            EXPECT_NE(s.to_ini().find("\n# " + p.key.substr(p.key.find('.') + 1) + " = "),
                      std::string::npos)
                << context;
            s.set(p.key, s.text(p.key), "--set");
            try {
              s.drop_inapplicable();
              ADD_FAILURE() << "--set " << p.key << " accepted where " << context;
            } catch (const Error& e) {
              EXPECT_EQ(std::string(e.what()).rfind("--set " + p.key + "=", 0), 0u)
                  << context << ": " << e.what();
            }
          }
          if (!tried) untried.insert(p.key + " with " + c.controller + " = " + excluded);
        }
      }
    }
  }
  EXPECT_GT(contexts, 200);
  std::string list;
  for (const auto& u : untried) list += "\n  " + u;
  EXPECT_TRUE(untried.empty()) << "no shipped scene gives these contexts:" << list;
}

TEST(SceneDeclarations, EveryApplicabilityRuleCanBeReadAndExplained) {
  // A rule either lists controller values (checked against the controller's row when the
  // table is built) or gives its own test and reason.
  for (const ParamSpec& p : parameter_table())
    for (const Requirement& r : p.applies_when) {
      EXPECT_TRUE(!r.any_of.empty() || (r.holds && r.why_not)) << p.key;
      for (const KeyCondition& c : r.any_of) {
        ASSERT_NE(find_param(c.controller), nullptr) << p.key;
        EXPECT_FALSE(c.allowed().empty()) << p.key;
      }
    }
}
