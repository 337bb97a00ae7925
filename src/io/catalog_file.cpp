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
  CsvCatalog(const std::string& path, bool append)
      : csv_(path, catalog_header(), append, CsvStream::kWhenFull),
        checksum_(fnv1a64(catalog_header() + "\n")) {}
  std::optional<std::uint64_t> checksum() const override { return checksum_; }
  void set_checksum(std::uint64_t sum) override { checksum_ = sum; }
  void append(const EventRecord& e) override {
    char* begin = csv_.begin_row(kMaxCatalogRow);
    char* end = catalog_row_to(begin, e);
    checksum_ = fnv1a64("\n", fnv1a64(std::string_view(begin, end - begin), checksum_));
    csv_.end_row(end);
  }
  void flush() override { csv_.flush(); }
  std::uint64_t sync() override { return csv_.sync(); }
  void close() override { csv_.close(); }

 private:
  CsvStream csv_;
  std::uint64_t checksum_;  // fnv1a64 of every byte written to the file so far
};

class H5Catalog : public CatalogFile {
 public:
  H5Catalog(const std::string& path,
            const std::vector<std::pair<std::string, std::string>>& attributes,
            std::int64_t resumed_rows)
      : h5_(path, attributes, resumed_rows) {}
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
    const std::vector<std::pair<std::string, std::string>>& attributes, std::int64_t resumed_rows) {
  switch (format) {
    case CatalogFormat::Csv:
      return std::make_unique<CsvCatalog>(path, resumed_rows >= 0);
    case CatalogFormat::Hdf5:
      return std::make_unique<H5Catalog>(path, attributes, resumed_rows);
    case CatalogFormat::None:
      break;
  }
  throw Error("open_catalog_file: output.catalog = none writes no file");
}

}  // namespace bkq
