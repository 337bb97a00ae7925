// Output writers: the catalogue schema and rows, the JSON writer, the output folder's
// guards, atomic files and streamed CSVs (including what happens when a write fails).
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "../cli_helpers.hpp"
#include "core/error.hpp"
#include "io/catalog.hpp"
#include "io/json.hpp"
#include "io/output.hpp"
#include "io/scene.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::string cur;
  std::istringstream in(s);
  while (std::getline(in, cur, sep)) parts.push_back(cur);
  return parts;
}

TEST(Catalog, HeaderFollowsSchemaAndContract) {
  EXPECT_EQ(catalog_header(),
            "event,load,trigger,blocks,moment,magnitude,duration,max_speed,pad_displacement,"
            "first_block,last_block,energy_residual");
  for (const auto& c : catalog_schema()) EXPECT_STRNE(c.doc, "") << c.name;
}

TEST(Catalog, RowRoundTripsEveryNumber) {
  EventRecord e;
  e.event = 123456789012LL;
  e.load = 0.1 + 0.2;
  e.trigger = 17;
  e.blocks = 4;
  e.moment = 1.0 / 3.0;
  e.magnitude = std::log(1.0 / 3.0);
  e.duration = 1e-300;
  e.max_speed = 12345.678901234567;
  e.pad_displacement = -2.5e-7;
  e.first_block = 15;
  e.last_block = 18;
  e.energy_residual = 0;
  const auto f = split(catalog_row(e), ',');
  ASSERT_EQ(f.size(), catalog_schema().size());
  EXPECT_EQ(f[0], "123456789012");
  EXPECT_EQ(std::strtod(f[1].c_str(), nullptr), e.load);
  EXPECT_EQ(f[2], "17");
  EXPECT_EQ(f[3], "4");
  EXPECT_EQ(std::strtod(f[4].c_str(), nullptr), e.moment);
  EXPECT_EQ(std::strtod(f[5].c_str(), nullptr), e.magnitude);
  EXPECT_EQ(std::strtod(f[6].c_str(), nullptr), e.duration);
  EXPECT_EQ(std::strtod(f[7].c_str(), nullptr), e.max_speed);
  EXPECT_EQ(std::strtod(f[8].c_str(), nullptr), e.pad_displacement);
  EXPECT_EQ(f[9], "15");
  EXPECT_EQ(f[10], "18");
  EXPECT_EQ(f[11], "0");
}

TEST(Json, OrderedPrettyEscapedRoundTripNumbers) {
  Json inner = Json::array();
  inner.push(Json::integer(1)).push(Json::number(0.5)).push(Json::null());
  Json o = Json::object();
  o.set("events", std::int64_t{100000})
      .set("b_mle", 0.1 + 0.2)
      .set("name", "a \"quoted\"\\path\n\x01")
      .set("ok", true)
      .set("whole", 2.0)
      .set("bad", std::numeric_limits<double>::quiet_NaN())
      .set("list", inner)
      .set("empty", Json::object());
  o.set("events", 7);  // replacing keeps the place
  EXPECT_EQ(o.str(),
            "{\n"
            "  \"events\": 7,\n"
            "  \"b_mle\": 0.30000000000000004,\n"
            "  \"name\": \"a \\\"quoted\\\"\\\\path\\n\\u0001\",\n"
            "  \"ok\": true,\n"
            "  \"whole\": 2.0,\n"
            "  \"bad\": null,\n"
            "  \"list\": [\n"
            "    1,\n"
            "    0.5,\n"
            "    null\n"
            "  ],\n"
            "  \"empty\": {}\n"
            "}");
}

TEST(FormatReal, ShortestRoundTrip) {
  EXPECT_EQ(format_real(0.1), "0.1");
  EXPECT_EQ(format_real(100), "100");
  EXPECT_EQ(format_real(-2.5e-7), "-2.5e-07");
  EXPECT_EQ(format_real(std::numeric_limits<double>::infinity()), "inf");
  const double x = 0.0833333333333333;
  EXPECT_EQ(std::strtod(format_real(x).c_str(), nullptr), x);
}

TEST(OutputFolder, CreatesParentsAndGivesPaths) {
  test::TempDir tmp;
  const std::string dir = tmp.file("a/b/c");
  OutputFolder out(dir, false, false);
  EXPECT_TRUE(fs::is_directory(dir));
  EXPECT_EQ(out.path("catalog.csv"), dir + "/catalog.csv");
  EXPECT_EQ(out.dir(), dir);
  // The probe leaves nothing behind; the lock goes with the folder object.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  EXPECT_TRUE(fs::exists(dir + "/bkquake.lock"));
}

// A process killed while probing a folder on a file system without unnamed files leaves
// the named probe; the next opening of the folder removes it (it once stood among a resumed
// sweep's files, which then differed from the straight sweep's).
TEST(OutputFolder, RemovesAProbeThatAKillLeftBehind) {
  for (bool resume : {false, true}) {
    test::TempDir tmp;
    const std::string dir = tmp.file("out");
    fs::create_directory(dir);
    const std::string stale = dir + "/.bkquake-probe-AbC123";
    std::ofstream(stale) << "";
    ASSERT_TRUE(fs::exists(stale));
    OutputFolder out(dir, false, resume);
    EXPECT_FALSE(fs::exists(stale)) << "resume " << resume;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  }
}

// A write cut short by a kill leaves its temporary (NAME.bkquake-tmp-XXXXXX) beside the file:
// a run that takes the folder over (--resume, --force) removes it, and nothing else that
// merely looks like a temporary (a user's file, an export's; the folder lock's own are
// FolderLock's: TakingTheLockRemovesTheTemporaryOfAKilledAttempt);
// a new run in the folder refuses it as a file it did not write, and removes nothing.
TEST(OutputFolder, TakingTheFolderOverRemovesTheTemporariesOfCutWrites) {
  for (bool resume : {false, true}) {
    test::TempDir tmp;
    const std::string dir = tmp.file("out");
    fs::create_directory(dir);
    const std::string cut = dir + "/summary.json" + kTempMarker + "Ab12Cd";
    const std::vector<std::string> kept = {dir + "/notes.tmp-1.txt", dir + "/results.tmp-backup",
                                           dir + "/data.tmp-2024q1", dir + "/x.csv.tmp-123456"};
    std::ofstream(cut) << "{";
    for (const std::string& f : kept) std::ofstream(f) << "mine";
    EXPECT_THROW(OutputFolder(dir, false, false), Error);
    EXPECT_TRUE(fs::exists(cut));
    OutputFolder out(dir, !resume, resume);
    EXPECT_FALSE(fs::exists(cut)) << "resume " << resume;
    for (const std::string& f : kept) EXPECT_TRUE(fs::exists(f)) << f << ", resume " << resume;
  }
}

TEST(OutputFolder, WriteTemporariesCarryTheMarkerAndNothingElseMatches) {
  test::TempDir tmp;
  const std::string target = tmp.file("catalog.csv");
  const std::string t = write_temp_beside(target, "x");
  EXPECT_TRUE(is_write_temporary(fs::path(t).filename().string())) << t;
  EXPECT_EQ(fs::path(t).filename().string().rfind(std::string("catalog.csv") + kTempMarker, 0), 0u);
  for (const char* name :
       {"catalog.csv", "catalog.csv.tmp-Ab12Cd", ".bkquake.lock.tmp-Ab12Cd", "a.bkquake-tmp-Ab12C",
        "a.bkquake-tmp-Ab12Cd7", "a.bkquake-tmp-Ab-2Cd", ".bkquake-tmp-Ab12Cd"})
    EXPECT_FALSE(is_write_temporary(name)) << name;
  remove_temporaries_of(target);
  EXPECT_FALSE(fs::exists(t));
}

TEST(OutputFolder, RefusesAPathUnderARegularFile) {
  test::TempDir tmp;
  const std::string file = tmp.write("plain", "x");
  try {
    OutputFolder(file + "/sub", false, false);
    FAIL() << "expected bkq::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot create output folder '" + file + "/sub'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(OutputFolder(file, false, false), Error);
}

TEST(OutputFolder, RefusesAReadOnlyFolder) {
  if (::geteuid() == 0) GTEST_SKIP() << "root can write anywhere";
  test::TempDir tmp;
  const std::string dir = tmp.file("ro");
  fs::create_directory(dir);
  ::chmod(dir.c_str(), 0555);
  EXPECT_THROW(OutputFolder(dir, false, false), Error);
  ::chmod(dir.c_str(), 0755);
}

TEST(OutputFolder, GuardsAFinishedRun) {
  test::TempDir tmp;
  tmp.write("summary.json", "{}");
  try {
    OutputFolder(tmp.path().string(), false, false);
    FAIL() << "expected bkq::Error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "output folder '" + tmp.path().string() +
                  "' already holds a finished run (summary.json); use --force to overwrite or "
                  "--resume to continue");
  }
  EXPECT_NO_THROW(OutputFolder(tmp.path().string(), true, false));
  EXPECT_NO_THROW(OutputFolder(tmp.path().string(), false, true));
}

TEST(WriteFileAtomic, WritesReplacesAndReportsErrors) {
  test::TempDir tmp;
  const std::string p = tmp.file("summary.json");
  write_file_atomic(p, "first");
  write_file_atomic(p, "second\n");
  EXPECT_EQ(test::read_file(p), "second\n");
  // Only the file itself: no temporaries left over.
  EXPECT_EQ(std::distance(fs::directory_iterator(tmp.path()), fs::directory_iterator()), 1);
  try {
    write_file_atomic(tmp.file("missing/x.json"), "x");
    FAIL() << "expected bkq::Error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("missing/x.json"), std::string::npos) << msg;
    EXPECT_NE(msg.find("No such file or directory"), std::string::npos) << msg;
  }
}

TEST(Provenance, NamesVersionSeedSceneAndTime) {
  Scene s;
  s.set("run.seed", "77");
  const auto lines = provenance_lines(s);
  ASSERT_GE(lines.size(), 4u);
  EXPECT_EQ(lines[0].rfind("bkquake ", 0), 0u);
  EXPECT_NE(lines[0].find("(git "), std::string::npos);
  EXPECT_EQ(lines[1], "seed 77");
  // The built-in default changed by --set says what it became (Scene::provenance).
  EXPECT_EQ(lines[2], "scene built-in default with --set overrides (carlson-langer, event-driven)");
  bool has_time = false;
  for (const auto& l : lines) has_time |= l.rfind("written ", 0) == 0 && l.back() == 'Z';
  EXPECT_TRUE(has_time);
  // Provenance goes into scene.ini as comments, which still read back to the same scene.
  EXPECT_EQ(Scene::from_text(s.to_ini(lines), "scene.ini"), s);
}

TEST(CsvStream, HeaderFirstRowsAndAppend) {
  test::TempDir tmp;
  const std::string p = tmp.file("catalog.csv");
  {
    CsvStream csv(p, "a,b", false, 2);
    csv.row("1,2");
    csv.row("3,4");
    csv.row("5,6");
    EXPECT_EQ(csv.rows(), 3u);
    csv.close();
    csv.close();
  }
  EXPECT_EQ(test::read_file(p), "a,b\n1,2\n3,4\n5,6\n");
  {
    CsvStream csv(p, "a,b", true);
    csv.row("7,8");
  }
  EXPECT_EQ(test::read_file(p), "a,b\n1,2\n3,4\n5,6\n7,8\n");
  { CsvStream csv(p, "a,b", false); }
  EXPECT_EQ(test::read_file(p), "a,b\n");
  EXPECT_THROW(CsvStream(p, "x,y", true), Error);
  // Appending to a file that does not exist yet starts it with the header.
  { CsvStream csv(tmp.file("new.csv"), "a,b", true); }
  EXPECT_EQ(test::read_file(tmp.file("new.csv")), "a,b\n");
}

TEST(CsvStream, FlushesEarlyEnoughToReadWhileRunning) {
  test::TempDir tmp;
  const std::string p = tmp.file("t.csv");
  CsvStream csv(p, "t", false, 2);
  csv.row("1");
  csv.row("2");
  EXPECT_EQ(test::read_file(p), "t\n1\n2\n");
}

TEST(CsvStream, RowsFormattedInPlaceAcrossBuffersKeepTheirOrder) {
  test::TempDir tmp;
  const std::string p = tmp.file("big.csv");
  CsvStream csv(p, "i,x", false, CsvStream::kWhenFull);
  std::string want = "i,x\n";
  for (int i = 0; i < 60000; ++i) {
    const std::string line =
        std::to_string(i) + "," + std::string(40, static_cast<char>('a' + i % 26));
    want += line + "\n";
    if (i % 2) {
      csv.row(line);
    } else {
      char* out = csv.begin_row(line.size());
      csv.end_row(std::copy(line.begin(), line.end(), out));
    }
  }
  ASSERT_GT(want.size(), 2 * CsvStream::kBufferBytes);
  // Written in whole buffers: what is on disk so far is a prefix ending with a whole row.
  const std::string part = test::read_file(p);
  EXPECT_GT(part.size(), CsvStream::kBufferBytes / 2);
  EXPECT_LT(part.size(), want.size());
  EXPECT_EQ(part, want.substr(0, part.size()));
  EXPECT_EQ(part.back(), '\n');
  EXPECT_EQ(csv.sync(), want.size());
  csv.close();
  EXPECT_EQ(test::read_file(p), want);
}

TEST(CsvStream, WriteFailureNamesTheFile) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  try {
    CsvStream csv("/dev/full", "a,b", false, 1);
    csv.row("1,2");
    csv.close();
    FAIL() << "expected bkq::Error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("/dev/full"), std::string::npos) << msg;
    EXPECT_NE(msg.find("No space left on device"), std::string::npos) << msg;
  }
  EXPECT_THROW(CsvStream("/nonexistent-bkquake-dir/x.csv", "a", false), Error);
}

}  // namespace
}  // namespace bkq
