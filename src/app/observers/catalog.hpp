// The event catalogue as an observer: one row per recorded event (event runs) or slip
// episode (continuous runs), streamed to the file of the scene's output.catalog
// (io/catalog_file.hpp: catalog.csv or catalog.h5; with none no observer is attached). A
// checkpoint syncs the file first and records how much of it belongs to it (the bytes of
// catalog.csv; catalog.h5's rows are the events done), so a resumed run continues after it,
// and a checksum of those rows (both formats), so a resume finds a row edited in between.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/observers/observer.hpp"
#include "io/catalog_file.hpp"

namespace bkq {

class Scene;

class CatalogWriter : public RunObserver {
 public:
  // `resumed_rows` >= 0: continue the file of a resumed run after that many rows (a csv
  // file is already cut back to its checkpoint). `scene`: for catalog.h5's attributes.
  // `deflate`: compress a new catalog.h5 (output.catalog = hdf5-deflate).
  // `layout`: the columns beyond the common ones (the OFC catalogue's topplings, a
  // lattice's rows).
  CatalogWriter(CatalogFormat format, std::string path, const Scene& scene,
                std::int64_t resumed_rows = -1, bool deflate = false, CatalogLayout layout = {});
  void on_resume(const Checkpoint& c) override;
  void on_start() override;
  void on_event(const EventRecord& e) override;
  void on_phase_end(const Advance&) override;
  void on_checkpoint(Checkpoint& c) override;
  void on_end(const RunEnd&) override;

 private:
  CatalogFormat format_;
  std::string path_;
  std::vector<std::pair<std::string, std::string>> attributes_;
  std::int64_t resumed_rows_;
  bool deflate_;
  CatalogLayout layout_;
  std::unique_ptr<CatalogFile> file_;
  std::optional<std::uint64_t> saved_checksum_;  // of the rows a resumed run continues
};

// The checksum of catalog.csv's first catalog_bytes bytes saved in `c`, if it has one.
std::optional<std::uint64_t> saved_catalog_checksum(const Checkpoint& c);

}  // namespace bkq
