// catalog.h5 without HDF5 (see catalog_h5.hpp): compiled only when the build does not find
// HDF5 (CMakeLists.txt, bkquake_extra_unit), in place of catalog_h5_hdf5.cpp. Every
// function throws that output.catalog = hdf5 is not available.
#include "core/error.hpp"
#include "io/catalog_h5.hpp"

namespace bkq {

namespace {
[[noreturn]] void unavailable() {
  throw Error(
      "output.catalog = hdf5: this bkquake was built without HDF5 (install libhdf5-dev and "
      "rebuild); allowed here: csv, none");
}
}  // namespace

bool hdf5_available() {
  return false;
}
struct CatalogH5Writer::Impl {};
CatalogH5Writer::CatalogH5Writer(const std::string&,
                                 const std::vector<std::pair<std::string, std::string>>&,
                                 std::int64_t, int, CatalogLayout) {
  unavailable();
}
CatalogH5Writer::~CatalogH5Writer() = default;
void CatalogH5Writer::append(const EventRecord&) {}
std::uint64_t CatalogH5Writer::checksum() const {
  return 0;
}
void CatalogH5Writer::set_checksum(std::uint64_t) {}
std::int64_t CatalogH5Writer::sync() {
  return 0;
}
void CatalogH5Writer::close() {}
void check_catalog_h5(const std::string&, std::int64_t, std::optional<std::uint64_t>,
                      CatalogLayout) {
  unavailable();
}
struct CatalogH5Reader::Impl {};
CatalogH5Reader::CatalogH5Reader(const std::string&, const std::vector<std::string>&) {
  unavailable();
}
CatalogH5Reader::~CatalogH5Reader() = default;
bool CatalogH5Reader::has(std::size_t) const {
  return false;
}
std::int64_t CatalogH5Reader::rows() const {
  return 0;
}
std::int64_t CatalogH5Reader::next_block(std::vector<double>&) {
  return 0;
}

}  // namespace bkq
