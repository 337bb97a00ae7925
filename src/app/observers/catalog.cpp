// The catalog writer; see catalog.hpp.
#include "app/observers/catalog.hpp"

#include "io/catalog.hpp"
#include "io/checkpoint.hpp"

namespace bkq {

CatalogWriter::CatalogWriter(std::string path, bool append)
    : path_(std::move(path)), append_(append) {}

void CatalogWriter::on_start() {
  csv_ = std::make_unique<CsvStream>(path_, catalog_header(), append_);
}

void CatalogWriter::on_event(const EventRecord& e) {
  csv_->row(catalog_row(e));
}

// Synced first, so a checkpoint never counts rows that are not on disk.
void CatalogWriter::on_checkpoint(Checkpoint& c) {
  c.progress.catalog_bytes = csv_->sync();
}

void CatalogWriter::on_end(const RunEnd&) {
  csv_->close();
}

}  // namespace bkq
