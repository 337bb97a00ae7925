// catalog.csv as an observer: one row per recorded event (event runs) or slip episode
// (continuous runs), streamed; the columns are io/catalog.hpp's schema. A checkpoint
// records how many bytes of the file belong to it, so a resumed run appends after them, and
// a checksum of those bytes, so a resume finds a row edited in between.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "app/observers/observer.hpp"
#include "io/output.hpp"

namespace bkq {

class CatalogWriter : public RunObserver {
 public:
  // `append`: continue the file of a resumed run (already cut back to its checkpoint).
  CatalogWriter(std::string path, bool append);
  void on_resume(const Checkpoint& c) override;
  void on_start() override;
  void on_event(const EventRecord& e) override;
  void on_checkpoint(Checkpoint& c) override;
  void on_end(const RunEnd&) override;

 private:
  std::string path_;
  bool append_;
  std::unique_ptr<CsvStream> csv_;
  std::uint64_t checksum_ = 0;  // fnv1a64 of every byte written to the file so far
};

// The checksum of catalog.csv's first catalog_bytes bytes saved in `c`, if it has one.
std::optional<std::uint64_t> saved_catalog_checksum(const Checkpoint& c);

}  // namespace bkq
