// The catalog writer; see catalog.hpp.
#include "app/observers/catalog.hpp"

#include "io/catalog.hpp"
#include "io/checkpoint.hpp"

namespace bkq {

CatalogWriter::CatalogWriter(std::string path, bool append)
    : path_(std::move(path)), append_(append) {}

namespace {
constexpr const char* kChecksumState = "catalog.checksum";
}

std::optional<std::uint64_t> saved_catalog_checksum(const Checkpoint& c) {
  const std::string* bytes = c.find(kChecksumState);
  if (!bytes) return std::nullopt;  // a checkpoint written before checksums
  StateReader in(*bytes, kChecksumState);
  return in.u64();
}

// Resumed: the file holds exactly the checkpoint's bytes (run_scene checked them).
void CatalogWriter::on_resume(const Checkpoint& c) {
  if (const auto sum = saved_catalog_checksum(c)) checksum_ = *sum;
}

void CatalogWriter::on_start() {
  if (!append_) checksum_ = fnv1a64(catalog_header() + "\n");
  csv_ = std::make_unique<CsvStream>(path_, catalog_header(), append_);
}

void CatalogWriter::on_event(const EventRecord& e) {
  const std::string row = catalog_row(e);
  csv_->row(row);
  checksum_ = fnv1a64("\n", fnv1a64(row, checksum_));
}

// Synced first, so a checkpoint never counts rows that are not on disk.
void CatalogWriter::on_checkpoint(Checkpoint& c) {
  c.progress.catalog_bytes = csv_->sync();
  StateWriter out;
  out.u64(checksum_);
  c.put(kChecksumState, out.bytes());
}

void CatalogWriter::on_end(const RunEnd&) {
  csv_->close();
}

}  // namespace bkq
