// The catalogue reader: columns by header name, and errors that name the file and the
// line (zero or one event, non-positive moment, wrong field count, non-number, missing
// column). Also the event classes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "io/catalog_reader.hpp"
#include "io/run_folder.hpp"
#include "stats/event_classes.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;

const char* kHeader =
    "event,load,trigger,blocks,moment,magnitude,duration,max_speed,pad_displacement,"
    "first_block,last_block,energy_residual\n";

fs::path write_catalog(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("bkq_test_stats_" + name);
  fs::create_directories(dir);
  std::ofstream(dir / "catalog.csv") << text;
  return dir / "catalog.csv";
}

std::string row(int event, int blocks, const std::string& moment, int first, int last) {
  return std::to_string(event) + ",0.5,3," + std::to_string(blocks) + "," + moment +
         ",0,0.1,0.2,0," + std::to_string(first) + "," + std::to_string(last) + ",0\n";
}

// Reads every event and applies the fit's minimum-count rule; returns the error text.
std::string read_error(const fs::path& p) {
  try {
    CatalogReader r(p);
    CatalogEvent e;
    while (r.next(e)) {
    }
    require_events_to_fit(r.file(), r.events_read());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CatalogReader, ReadsColumnsByName) {
  // Columns in a different order from the schema.
  const auto p = write_catalog("order",
                               "moment,blocks,last_block,first_block,event\n"
                               "2.5,3,7,5,1\n1e-3,1,4,4,2\n");
  CatalogReader r(p);
  EXPECT_TRUE(r.has_extent());
  EXPECT_FALSE(r.has_load());
  CatalogEvent e;
  ASSERT_TRUE(r.next(e));
  EXPECT_EQ(e.blocks, 3);
  EXPECT_EQ(e.first_block, 5);
  EXPECT_EQ(e.last_block, 7);
  EXPECT_DOUBLE_EQ(e.magnitude, std::log(2.5));
  ASSERT_TRUE(r.next(e));
  EXPECT_EQ(e.event, 2);
  EXPECT_FALSE(r.next(e));
  EXPECT_EQ(r.events_read(), 2);
}

TEST(CatalogReader, ZeroOrOneEventIsAnError) {
  const auto p0 = write_catalog("zero", kHeader);
  EXPECT_EQ(read_error(p0), p0.string() + ": need at least 2 events to fit, found 0");
  const auto p1 = write_catalog("one", std::string(kHeader) + row(1, 1, "0.3", 4, 4));
  EXPECT_EQ(read_error(p1), p1.string() + ": need at least 2 events to fit, found 1");
  const auto pe = write_catalog("empty", "");
  EXPECT_NE(read_error(pe).find("empty file"), std::string::npos);
}

TEST(CatalogReader, NonPositiveMomentNamesTheLine) {
  const auto p = write_catalog(
      "negative", std::string(kHeader) + row(1, 1, "0.3", 4, 4) + row(2, 1, "-0.3", 4, 4));
  EXPECT_EQ(read_error(p), p.string() + " line 3: moment must be > 0, got -0.3");
  const auto z = write_catalog("zero_moment", std::string(kHeader) + row(1, 1, "0", 4, 4));
  EXPECT_EQ(read_error(z), z.string() + " line 2: moment must be > 0, got 0");
}

TEST(CatalogReader, MalformedRowsNameTheLine) {
  const auto p =
      write_catalog("fields", std::string(kHeader) + row(1, 1, "0.3", 4, 4) + "2,0.5,3,1,0.3\n");
  EXPECT_EQ(read_error(p), p.string() + " line 3: expected 12 fields, got 5");
  const auto q = write_catalog("nan", std::string(kHeader) + row(1, 1, "0.3", 4, 4) +
                                          row(2, 1, "0.3", 4, 4) + row(3, 1, "abc", 4, 4));
  EXPECT_EQ(read_error(q), q.string() + " line 4: column 'moment': expected a number, got 'abc'");
  const auto r = write_catalog(
      "int", std::string(kHeader) + row(1, 1, "0.3", 4, 4) + "2,0.5,3,two,0.3,0,0,0,0,4,4,0\n");
  EXPECT_EQ(read_error(r), r.string() + " line 3: column 'blocks': expected a number, got 'two'");
}

TEST(CatalogReader, MissingColumnIsAnError) {
  const auto p = write_catalog("missing", "event,load,blocks\n1,0.1,2\n");
  EXPECT_NE(read_error(p).find(p.string() + ": missing column 'moment'"), std::string::npos);
}

TEST(EventClasses, Definitions) {
  const int n = 100;
  EXPECT_EQ(classify_event(1, 0, 0, n, Boundary::Free), EventClass::single_block);
  EXPECT_EQ(classify_event(5, 10, 14, n, Boundary::Free), EventClass::localised);
  EXPECT_EQ(classify_event(5, 0, 4, n, Boundary::Free), EventClass::delocalised);
  EXPECT_EQ(classify_event(5, 95, 99, n, Boundary::Free), EventClass::delocalised);
  EXPECT_EQ(classify_event(5, 0, 4, n, Boundary::Periodic), EventClass::localised);
  EXPECT_EQ(classify_event(99, 0, 98, n, Boundary::Periodic), EventClass::delocalised);
  // A lattice of 20 x 10 = 200 sites: by sites toppled and the bounding box.
  EXPECT_EQ(classify_lattice_event(1, 0, 0, 0, 0, 20, 10), EventClass::single_block);
  EXPECT_EQ(classify_lattice_event(12, 3, 7, 2, 5, 20, 10), EventClass::localised);
  EXPECT_EQ(classify_lattice_event(12, 0, 19, 4, 4, 20, 10), EventClass::delocalised);
  EXPECT_EQ(classify_lattice_event(12, 5, 6, 0, 9, 20, 10), EventClass::delocalised);
  EXPECT_EQ(classify_lattice_event(99, 1, 18, 1, 8, 20, 10), EventClass::localised);
  EXPECT_EQ(classify_lattice_event(100, 1, 18, 1, 8, 20, 10), EventClass::delocalised);
  // An edge touched is not enough (unlike a chain's free end): the box must span an axis.
  EXPECT_EQ(classify_lattice_event(5, 0, 4, 0, 1, 20, 10), EventClass::localised);
  EventClassCounts c;
  c.add(EventClass::single_block);
  c.add(EventClass::single_block);
  c.add(EventClass::localised);
  c.add(EventClass::delocalised);
  EXPECT_EQ(c.total(), 4);
  EXPECT_DOUBLE_EQ(c.fraction(EventClass::single_block), 0.5);
  EXPECT_THROW(parse_boundary("open"), Error);
}

}  // namespace
}  // namespace bkq
