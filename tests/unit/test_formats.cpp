// The one JSON writer's two number styles and inline arrays, its top-level number reader, the
// one INI parser, the run-folder reader on the scene.ini files of finished runs, and the
// schema lookups the CSV readers use.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "io/catalog.hpp"
#include "io/csv_util.hpp"
#include "io/ini.hpp"
#include "io/json.hpp"
#include "io/run_folder.hpp"
#include "io/scene.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;

TEST(Json, ShortestRealsAndInlineArrays) {
  Json o = Json::object();
  o.set("mu_min", Json::number(-8.0, Json::Real::shortest))
      .set("point", Json::number(-8.0))
      .set("bad", Json::number(std::numeric_limits<double>::infinity(), Json::Real::shortest))
      .set("merged_from", Json::strings({"a", "b \"c\""}))
      .set("notes", Json::strings({}));
  EXPECT_EQ(o.str(),
            "{\n"
            "  \"mu_min\": -8,\n"
            "  \"point\": -8.0,\n"
            "  \"bad\": null,\n"
            "  \"merged_from\": [\"a\", \"b \\\"c\\\"\"],\n"
            "  \"notes\": []\n"
            "}");
}

TEST(Json, TopLevelNumbersOnly) {
  const std::string text =
      "{\n  \"fit\": {\"events\": 5, \"s\": \"events\"},\n  \"name\": \"events\",\n"
      "  \"list\": [1, {\"events\": 6}],\n  \"events\": 3000,\n  \"b\": null,\n"
      "  \"x\": -1.5e-3,\n  \"w\": \"0.2\"\n}";
  EXPECT_EQ(json_top_level_number(text, "events", "s.json"), 3000.0);
  EXPECT_EQ(json_top_level_number(text, "x", "s.json"), -1.5e-3);
  EXPECT_EQ(json_top_level_number(text, "b", "s.json"), std::nullopt);
  EXPECT_EQ(json_top_level_number(text, "missing", "s.json"), std::nullopt);
  EXPECT_THROW(json_top_level_number(text, "w", "s.json"), Error);
  EXPECT_THROW(json_top_level_number("[1, 2]", "w", "s.json"), Error);
  EXPECT_THROW(json_top_level_number("{\"a\": ", "w", "s.json"), Error);
  EXPECT_EQ(json_top_level_number("{}", "w", "s.json"), std::nullopt);
}

TEST(Ini, SectionsCommentsAndOrder) {
  const auto e = parse_ini("# top\n[model]\nblocks = 50 \n# c\n\n[friction]\nlaw=thesis\n", "x");
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].key, "model.blocks");
  EXPECT_EQ(e[0].value, "50");
  EXPECT_EQ(e[1].key, "friction.law");
  EXPECT_EQ(e[1].value, "thesis");
  try {
    parse_ini("[model]\nno equals sign\n", "in s.ini");
    FAIL();
  } catch (const Error& err) {
    EXPECT_NE(std::string(err.what()).find("(in s.ini)"), std::string::npos) << err.what();
  }
}

TEST(RunFolder, ReadsTheSceneOfEveryRecordedRun) {
  // The golden scene.ini files were written by an earlier bkquake: they must still read,
  // both through the run-folder reader and as scenes.
  int n = 0;
  for (const auto& dir : fs::directory_iterator(fs::path(BKQUAKE_SOURCE_DIR) / "tests/golden")) {
    const fs::path ini = dir.path() / "scene.ini";
    if (!fs::exists(ini)) continue;
    ++n;
    SCOPED_TRACE(ini.string());
    const Scene scene = Scene::from_file(ini.string());
    const SceneModelInfo info = read_scene_model(ini);
    EXPECT_EQ(info.boundary.value_or("free"), scene.choice("model.boundary"));
    if (scene.applies("model.blocks")) {
      EXPECT_EQ(info.blocks, scene.integer("model.blocks"));
    }
  }
  EXPECT_GE(n, 10);
}

TEST(RunFolder, PartialAndForeignScenesRead) {
  const fs::path dir = fs::temp_directory_path() / "bkq_test_formats_run_folder";
  fs::create_directories(dir);
  // Keys unknown today (an older or newer bkquake) are skipped; the needed ones are checked.
  std::ofstream(dir / "scene.ini") << "# old\n[model]\nblocks = 50\nboundary = periodic\n"
                                   << "retired_key = 3\n[friction]\nalpha = 1\n";
  const SceneModelInfo info = read_scene_model(dir / "scene.ini");
  EXPECT_EQ(info.blocks, 50);
  EXPECT_EQ(info.boundary, "periodic");
  EXPECT_EQ(info.alpha, "1");
  EXPECT_EQ(parse_boundary(*info.boundary), Boundary::Periodic);
  EXPECT_THROW(parse_boundary("ring"), Error);
  std::ofstream(dir / "scene.ini") << "[model]\nblocks = -4\n";
  EXPECT_THROW(read_scene_model(dir / "scene.ini"), Error);
  EXPECT_THROW(read_scene_model(dir / "missing.ini"), Error);
}

TEST(Schema, ReadersFindColumnsByTheSchemasNames) {
  const std::vector<std::string_view> header = {"event", "moment", "extra"};
  EXPECT_EQ(csv::find_column(header, catalog_schema(), catalog_col::moment), 1);
  EXPECT_EQ(csv::find_column(header, catalog_schema(), catalog_col::load), -1);
  EXPECT_THROW(csv::find_column(header, catalog_schema(), "extra"), std::logic_error);
  EXPECT_THROW(csv::require_column(header, catalog_schema(), catalog_col::load, "c.csv"), Error);
  EXPECT_STREQ(column(catalog_schema(), catalog_col::event).format, kInteger);
}

}  // namespace
}  // namespace bkq
