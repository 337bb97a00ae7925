// The catalog writer; see catalog.hpp.
#include "app/observers/catalog.hpp"

#include "io/checkpoint.hpp"
#include "io/output.hpp"
#include "io/scene.hpp"

namespace bkq {

namespace {

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& line : lines) s += line + "\n";
  return s;
}

}  // namespace

CatalogWriter::CatalogWriter(CatalogFormat format, std::string path, const Scene& scene,
                             std::int64_t resumed_rows, bool deflate, CatalogLayout layout)
    : format_(format),
      path_(std::move(path)),
      resumed_rows_(resumed_rows),
      deflate_(deflate),
      layout_(layout) {
  if (format_ == CatalogFormat::Hdf5)
    attributes_ = {{"provenance", joined(provenance_lines(scene))}, {"scene", scene.to_ini()}};
}

namespace {
// "catalog.rowhash": line_hash of the rows (catalog.h5: of their cells; a checkpoint of an
// HDF5 run from before this has none and resumes unchecked). (The "catalog.checksum" of earlier
// revisions, FNV-1a by byte, is not read: such a checkpoint resumes without the check.)
constexpr const char* kChecksumState = "catalog.rowhash";
}  // namespace

std::optional<std::uint64_t> saved_catalog_checksum(const Checkpoint& c) {
  const std::string* bytes = c.find(kChecksumState);
  if (!bytes) return std::nullopt;  // a checkpoint written before checksums
  StateReader in(*bytes, kChecksumState);
  return in.u64();
}

// Resumed: the file holds exactly the checkpoint's bytes (run_scene checked them).
void CatalogWriter::on_resume(const Checkpoint& c) {
  saved_checksum_ = saved_catalog_checksum(c);
}

void CatalogWriter::on_start() {
  file_ = open_catalog_file(format_, path_, attributes_, resumed_rows_, deflate_, layout_);
  if (saved_checksum_) file_->set_checksum(*saved_checksum_);
}

void CatalogWriter::on_event(const EventRecord& e) {
  file_->append(e);
}

// The rows are all in the file before the end-of-run fit starts.
void CatalogWriter::on_phase_end(const Advance&) {
  file_->flush();
}

// Synced first, so a checkpoint never counts rows that are not on disk.
void CatalogWriter::on_checkpoint(Checkpoint& c) {
  c.progress.catalog_bytes = file_->sync();
  if (const auto sum = file_->checksum()) {
    StateWriter out;
    out.u64(*sum);
    c.put(kChecksumState, out.bytes());
  }
}

void CatalogWriter::on_end(const RunEnd&) {
  file_->close();
}

}  // namespace bkq
