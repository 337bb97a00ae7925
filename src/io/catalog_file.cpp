// The catalogue's formats behind one interface (see catalog_file.hpp).
#include "io/catalog_file.hpp"

#include <string_view>

#include "core/error.hpp"
#include "io/catalog.hpp"
#include "io/catalog_h5.hpp"
#include "io/checkpoint.hpp"
#include "io/output.hpp"

namespace bkq {

namespace {

class CsvCatalog : public CatalogFile {
 public:
  CsvCatalog(const std::string& path, bool append, CatalogLayout layout)
      : csv_(path, catalog_header(layout), append, CsvStream::kWhenFull),
        checksum_(line_hash(catalog_header(layout) + "\n", kLineHashSeed)),
        layout_(layout) {}
  std::optional<std::uint64_t> checksum() const override { return checksum_; }
  void set_checksum(std::uint64_t sum) override { checksum_ = sum; }
  void append(const EventRecord& e) override {
    char* begin = csv_.begin_row(kMaxCatalogRow);
    char* end = catalog_row_to(begin, e, layout_);
    *end = '\n';  // end_row writes it there too; hashed with the row
    checksum_ = line_hash(std::string_view(begin, end + 1 - begin), checksum_);
    csv_.end_row(end);
  }
  void flush() override { csv_.flush(); }
  std::uint64_t sync() override { return csv_.sync(); }
  void close() override { csv_.close(); }

 private:
  CsvStream csv_;
  std::uint64_t checksum_;  // line_hash of every line written to the file so far
  CatalogLayout layout_;    // the columns beyond the common ones
};

class H5Catalog : public CatalogFile {
 public:
  H5Catalog(const std::string& path,
            const std::vector<std::pair<std::string, std::string>>& attributes,
            std::int64_t resumed_rows, bool deflate, CatalogLayout layout)
      : h5_(path, attributes, resumed_rows, deflate ? 1 : 0, layout) {}
  std::optional<std::uint64_t> checksum() const override { return h5_.checksum(); }
  void set_checksum(std::uint64_t sum) override { h5_.set_checksum(sum); }
  void append(const EventRecord& e) override { h5_.append(e); }
  void flush() override { h5_.sync(); }
  std::uint64_t sync() override {
    h5_.sync();
    return 0;
  }
  void close() override { h5_.close(); }

 private:
  CatalogH5Writer h5_;
};

}  // namespace

const char* catalog_file_name(CatalogFormat format) {
  switch (format) {
    case CatalogFormat::Csv:
      return "catalog.csv";
    case CatalogFormat::Hdf5:
      return "catalog.h5";
    case CatalogFormat::None:
      break;
  }
  return nullptr;
}

std::unique_ptr<CatalogFile> open_catalog_file(
    CatalogFormat format, const std::string& path,
    const std::vector<std::pair<std::string, std::string>>& attributes, std::int64_t resumed_rows,
    bool deflate, CatalogLayout layout) {
  switch (format) {
    case CatalogFormat::Csv:
      return std::make_unique<CsvCatalog>(path, resumed_rows >= 0, layout);
    case CatalogFormat::Hdf5:
      return std::make_unique<H5Catalog>(path, attributes, resumed_rows, deflate, layout);
    case CatalogFormat::None:
      break;
  }
  throw Error("open_catalog_file: output.catalog = none writes no file");
}

}  // namespace bkq
