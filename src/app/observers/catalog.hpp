// catalog.csv as an observer: one row per recorded event (event runs) or slip episode
// (continuous runs), streamed; the columns are io/catalog.hpp's schema. A checkpoint
// records how many bytes of the file belong to it, so a resumed run appends after them.
#pragma once

#include <memory>
#include <string>

#include "app/observers/observer.hpp"
#include "io/output.hpp"

namespace bkq {

class CatalogWriter : public RunObserver {
 public:
  // `append`: continue the file of a resumed run (already cut back to its checkpoint).
  CatalogWriter(std::string path, bool append);
  void on_start() override;
  void on_event(const EventRecord& e) override;
  void on_checkpoint(Checkpoint& c) override;
  void on_end(const RunEnd&) override;

 private:
  std::string path_;
  bool append_;
  std::unique_ptr<CsvStream> csv_;
};

}  // namespace bkq
