// catalog.h5 with HDF5 (see catalog_h5.hpp): compiled only when the build finds HDF5
// (CMakeLists.txt, bkquake_extra_unit), in place of catalog_h5_none.cpp.
#include <hdf5.h>

#include <algorithm>
#include <cstring>
#include <string_view>

#include "core/error.hpp"
#include "core/fnv1a.hpp"
#include "io/catalog.hpp"
#include "io/catalog_h5.hpp"
#include "io/output.hpp"

namespace bkq {

namespace {

constexpr const char* kTable = "catalog";
constexpr hsize_t kChunkRows = 8192;
constexpr unsigned kMetadataReadAttempts = 4;

// Turns HDF5's automatic error printing off once: every failure becomes a bkq::Error.
void quiet_hdf5() {
  static const bool done = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

// An HDF5 identifier closed by its own close function.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  ~Handle() { reset(); }
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = o.id_;
      close_ = o.close_;
      o.id_ = H5I_INVALID_HID;
    }
    return *this;
  }
  // Closes now; returns false if closing failed.
  bool reset() {
    const bool ok = id_ < 0 || close_(id_) >= 0;
    id_ = H5I_INVALID_HID;
    return ok;
  }
  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }  // NOLINT: used as the id in HDF5 calls

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer close_ = nullptr;
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error("catalog '" + path + "': " + what);
}

Handle checked(hid_t id, Handle::Closer close, const std::string& path, const std::string& what) {
  if (id < 0) fail(path, what);
  return Handle(id, close);
}

void check(herr_t rc, const std::string& path, const std::string& what) {
  if (rc < 0) fail(path, what);
}

// The row type: the schema's columns in order, 8 bytes each (the OFC automaton's schema
// adds topplings after the common columns, a lattice of rows its row columns).
Handle row_type(const std::string& path, CatalogLayout layout) {
  const Schema& schema = catalog_schema(layout);
  Handle t = checked(H5Tcreate(H5T_COMPOUND, 8 * schema.size()), H5Tclose, path,
                     "cannot build the row type");
  for (std::size_t k = 0; k < schema.size(); ++k)
    check(H5Tinsert(t, schema[k].name, 8 * k,
                    schema[k].format == kInteger ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE),
          path, "cannot build the row type");
  return t;
}

Handle file_access(const std::string& path, bool clear_status) {
  Handle fapl = checked(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, path, "cannot set up HDF5");
  // SWMR needs the 1.10 file format.
  check(H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST), path,
        "cannot set up HDF5");
  // HDF5 retries a metadata read whose checksum fails, for a single-writer reader 100 times
  // with growing sleeps: on a damaged file that is a silent wait of many minutes. A few tries
  // cover a torn read of a file being written; a damaged file is then refused at once.
  check(H5Pset_metadata_read_attempts(fapl, kMetadataReadAttempts), path, "cannot set up HDF5");
  if (clear_status) {
    // A writer killed in SWMR mode leaves the file marked as open for writing; HDF5's own
    // h5clear clears that mark through this file-access property, and so does a resume.
    hbool_t clear = true;
    if (H5Pexist(fapl, "clear_status_flags") > 0)
      check(H5Pset(fapl, "clear_status_flags", &clear), path, "cannot set up HDF5");
  }
  return fapl;
}

// Opens the table of an existing file and checks it is a catalogue's: a compound type
// holding every column of the schema. Returns {file, dataset, rows}.
struct Opened {
  Handle file, table;
  hsize_t rows = 0;
};

Opened open_table(const std::string& path, bool write) {
  quiet_hdf5();
  if (!is_hdf5_file(path)) fail(path, "not an HDF5 file (damaged, or not written by bkquake)");
  Opened o;
  const Handle fapl = file_access(path, write);
  hid_t file = H5Fopen(path.c_str(), write ? H5F_ACC_RDWR : H5F_ACC_RDONLY, fapl);
  // A file whose writer was killed is still marked as being written: a reader opens it as
  // a single-writer reader does.
  if (file < 0 && !write) file = H5Fopen(path.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, fapl);
  o.file = checked(file, H5Fclose, path, "cannot be opened as HDF5 (damaged)");
  if (H5Lexists(o.file, kTable, H5P_DEFAULT) <= 0)
    fail(path, std::string("no table '") + kTable + "' (not a bkquake catalogue)");
  o.table = checked(H5Dopen2(o.file, kTable, H5P_DEFAULT), H5Dclose, path,
                    std::string("cannot open the table '") + kTable + "' (damaged)");
  const Handle type =
      checked(H5Dget_type(o.table), H5Tclose, path, "cannot read the table's row type");
  if (H5Tget_class(type) != H5T_COMPOUND) fail(path, "the table's rows are not a compound type");
  const Handle space =
      checked(H5Dget_space(o.table), H5Sclose, path, "cannot read the table's size (damaged)");
  if (H5Sget_simple_extent_ndims(space) != 1) fail(path, "the table is not one-dimensional");
  check(H5Sget_simple_extent_dims(space, &o.rows, nullptr), path, "cannot read the table's size");
  return o;
}

void write_text_attribute(hid_t table, const std::string& path, const std::string& name,
                          const std::string& text) {
  const Handle type = checked(H5Tcopy(H5T_C_S1), H5Tclose, path, "cannot write attributes");
  check(H5Tset_size(type, text.empty() ? 1 : text.size()), path, "cannot write attributes");
  check(H5Tset_cset(type, H5T_CSET_UTF8), path, "cannot write attributes");
  const Handle space = checked(H5Screate(H5S_SCALAR), H5Sclose, path, "cannot write attributes");
  const Handle attr =
      checked(H5Acreate2(table, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              path, "cannot write the attribute '" + name + "'");
  check(H5Awrite(attr, type, text.empty() ? "" : text.data()), path,
        "cannot write the attribute '" + name + "'");
}

}  // namespace

bool hdf5_available() {
  return true;
}

struct CatalogH5Writer::Impl {
  std::string path;
  Handle file, table, type;
  hsize_t rows = 0;  // in the table
  std::vector<unsigned char> buf;
  std::size_t buffered = 0;
  bool closed = false;
  std::uint64_t checksum = kLineHashSeed;
  CatalogLayout layout;
  std::size_t columns = kCatalogColumns;  // kCatalogColumns + layout.extra_columns()

  // Writes the buffered rows at the end of the table.
  void write_buffer() {
    if (buffered == 0) return;
    const hsize_t start = rows, count = buffered, total = rows + buffered;
    check(H5Dset_extent(table, &total), path, "cannot extend the table");
    const Handle space = checked(H5Dget_space(table), H5Sclose, path, "cannot extend the table");
    check(H5Sselect_hyperslab(space, H5S_SELECT_SET, &start, nullptr, &count, nullptr), path,
          "cannot select rows");
    const Handle mem =
        checked(H5Screate_simple(1, &count, nullptr), H5Sclose, path, "cannot select rows");
    check(H5Dwrite(table, type, mem, space, H5P_DEFAULT, buf.data()), path, "cannot write rows");
    rows = total;
    buffered = 0;
  }
};

CatalogH5Writer::CatalogH5Writer(const std::string& path,
                                 const std::vector<std::pair<std::string, std::string>>& attributes,
                                 std::int64_t append_after, int deflate_level, CatalogLayout layout)
    : impl_(std::make_unique<Impl>()) {
  quiet_hdf5();
  Impl& w = *impl_;
  w.path = path;
  w.layout = layout;
  w.type = row_type(path, layout);
  w.columns = kCatalogColumns + layout.extra_columns();
  w.buf.resize(kChunkRows * 8 * w.columns);
  if (append_after >= 0) {
    refuse_link(path, "cannot append");
    Opened o = open_table(path, true);
    if (o.rows < static_cast<hsize_t>(append_after))
      fail(path, "holds " + std::to_string(o.rows) + " rows, the checkpoint counts " +
                     std::to_string(append_after));
    w.file = std::move(o.file);
    w.table = std::move(o.table);
    w.rows = static_cast<hsize_t>(append_after);
    check(H5Dset_extent(w.table, &w.rows), path, "cannot cut the table back to its checkpoint");
  } else {
    const Handle fapl = file_access(path, false);
    replace_link(path);  // H5F_ACC_TRUNC would write through it
    w.file = checked(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), H5Fclose, path,
                     "cannot create the file");
    const hsize_t zero = 0, unlimited = H5S_UNLIMITED;
    const Handle space =
        checked(H5Screate_simple(1, &zero, &unlimited), H5Sclose, path, "cannot create the table");
    const Handle dcpl =
        checked(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, path, "cannot create the table");
    check(H5Pset_chunk(dcpl, 1, &kChunkRows), path, "cannot create the table");
    if (deflate_level > 0) {
      check(H5Pset_shuffle(dcpl), path, "cannot create the table");
      check(H5Pset_deflate(dcpl, static_cast<unsigned>(deflate_level)), path,
            "cannot create the table");
    }
    w.table = checked(H5Dcreate2(w.file, kTable, w.type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
                      H5Dclose, path, "cannot create the table");
    for (const auto& [name, text] : attributes) write_text_attribute(w.table, path, name, text);
  }
  // From here on the file stays consistent on disk whenever the writer stops.
  check(H5Fstart_swmr_write(w.file), path, "cannot start HDF5's single-writer mode");
}

CatalogH5Writer::~CatalogH5Writer() {
  try {
    close();
  } catch (const Error&) {  // a destructor cannot report; close() does
  }
}

void CatalogH5Writer::append(const EventRecord& e) {
  Impl& w = *impl_;
  if (w.closed) fail(w.path, "write after close");
  const CatalogCells cells = catalog_cells(e);
  unsigned char* row = w.buf.data() + w.buffered * 8 * w.columns;
  for (std::size_t k = 0; k < kCatalogColumns; ++k) {
    if (cells[k].integer)
      std::memcpy(row + 8 * k, &cells[k].i, 8);
    else
      std::memcpy(row + 8 * k, &cells[k].x, 8);
  }
  CatalogCell extra[kMaxExtraColumns];
  const std::size_t n = catalog_extra_cells(e, w.layout, extra);
  for (std::size_t k = 0; k < n; ++k) {
    if (extra[k].integer)
      std::memcpy(row + 8 * (kCatalogColumns + k), &extra[k].i, 8);
    else
      std::memcpy(row + 8 * (kCatalogColumns + k), &extra[k].x, 8);
  }
  w.checksum =
      line_hash(std::string_view(reinterpret_cast<const char*>(row), 8 * w.columns), w.checksum);
  if (++w.buffered == kChunkRows) w.write_buffer();
}

std::int64_t CatalogH5Writer::sync() {
  Impl& w = *impl_;
  if (w.closed) fail(w.path, "sync after close");
  w.write_buffer();
  check(H5Fflush(w.file, H5F_SCOPE_GLOBAL), w.path, "cannot flush to disk");
  return static_cast<std::int64_t>(w.rows);
}

void CatalogH5Writer::close() {
  Impl& w = *impl_;
  if (w.closed) return;
  w.write_buffer();
  w.closed = true;
  const bool ok = w.table.reset() & w.type.reset();
  if (!(w.file.reset() && ok)) fail(w.path, "cannot close the file");
}

std::uint64_t CatalogH5Writer::checksum() const {
  return impl_->checksum;
}

void CatalogH5Writer::set_checksum(std::uint64_t sum) {
  impl_->checksum = sum;
}

void check_catalog_h5(const std::string& path, std::int64_t rows,
                      std::optional<std::uint64_t> checksum, CatalogLayout layout) {
  const Opened o = open_table(path, false);
  {
    // A table of other columns (a lattice's rows where the run has none, or the other way
    // round) is not the run's catalogue.
    const Handle file_type =
        checked(H5Dget_type(o.table), H5Tclose, path, "cannot read the table's row type");
    const int members = H5Tget_nmembers(file_type);
    if (members != static_cast<int>(kCatalogColumns + layout.extra_columns()))
      fail(path, "has " + std::to_string(members) + " columns, the run writes " +
                     std::to_string(kCatalogColumns + layout.extra_columns()) +
                     "; start over with --force");
  }
  if (o.rows < static_cast<hsize_t>(rows))
    fail(path, "holds " + std::to_string(o.rows) + " rows, the checkpoint counts " +
                   std::to_string(rows));
  if (!checksum) return;
  // The rows as the writer laid them out (row_type), hashed a block at a time.
  const Handle type = row_type(path, layout);
  const std::size_t row_bytes = 8 * (kCatalogColumns + layout.extra_columns());
  std::vector<unsigned char> buf;
  std::uint64_t hash = kLineHashSeed;
  for (hsize_t start = 0; start < static_cast<hsize_t>(rows);) {
    const hsize_t count = std::min<hsize_t>(65536, static_cast<hsize_t>(rows) - start);
    buf.assign(count * row_bytes, 0);
    const Handle space =
        checked(H5Dget_space(o.table), H5Sclose, path, "cannot read the table (damaged)");
    check(H5Sselect_hyperslab(space, H5S_SELECT_SET, &start, nullptr, &count, nullptr), path,
          "cannot select rows");
    const Handle mem =
        checked(H5Screate_simple(1, &count, nullptr), H5Sclose, path, "cannot select rows");
    check(H5Dread(o.table, type, mem, space, H5P_DEFAULT, buf.data()), path,
          "cannot read rows " + std::to_string(start) + ".." + std::to_string(start + count) +
              " (damaged)");
    for (hsize_t k = 0; k < count; ++k)
      hash = line_hash(
          std::string_view(reinterpret_cast<const char*>(buf.data() + k * row_bytes), row_bytes),
          hash);
    start += count;
  }
  if (hash != *checksum)
    fail(path, "its first " + std::to_string(rows) +
                   " rows are not those the checkpoint saw (their checksum differs: a row was "
                   "changed after the checkpoint); start over with --force");
}

struct CatalogH5Reader::Impl {
  std::string path;
  Opened o;
  Handle type;  // memory type: the present columns, as doubles
  std::vector<int> present;
  std::size_t columns = 0;
  hsize_t next = 0;
};

CatalogH5Reader::CatalogH5Reader(const std::string& path, const std::vector<std::string>& names)
    : impl_(std::make_unique<Impl>()) {
  Impl& r = *impl_;
  r.path = path;
  r.o = open_table(path, false);
  r.columns = names.size();
  const Handle file_type =
      checked(H5Dget_type(r.o.table), H5Tclose, path, "cannot read the table's row type");
  r.type = checked(H5Tcreate(H5T_COMPOUND, 8 * names.size()), H5Tclose, path,
                   "cannot build the row type");
  for (std::size_t k = 0; k < names.size(); ++k) {
    // A name outside the schemas is a bug.
    column(catalog_schema(kEveryCatalogColumn), names[k]);
    const bool in_file = H5Tget_member_index(file_type, names[k].c_str()) >= 0;
    r.present.push_back(in_file);
    if (in_file)
      check(H5Tinsert(r.type, names[k].c_str(), 8 * k, H5T_NATIVE_DOUBLE), path,
            "cannot build the row type");
  }
}

CatalogH5Reader::~CatalogH5Reader() = default;

bool CatalogH5Reader::has(std::size_t column) const {
  return impl_->present.at(column) != 0;
}

std::int64_t CatalogH5Reader::rows() const {
  return static_cast<std::int64_t>(impl_->o.rows);
}

std::int64_t CatalogH5Reader::next_block(std::vector<double>& out) {
  Impl& r = *impl_;
  if (r.next >= r.o.rows) return 0;
  const hsize_t start = r.next, count = std::min<hsize_t>(65536, r.o.rows - r.next);
  out.assign(count * r.columns, 0.0);
  const Handle space =
      checked(H5Dget_space(r.o.table), H5Sclose, r.path, "cannot read the table (damaged)");
  check(H5Sselect_hyperslab(space, H5S_SELECT_SET, &start, nullptr, &count, nullptr), r.path,
        "cannot select rows");
  const Handle mem =
      checked(H5Screate_simple(1, &count, nullptr), H5Sclose, r.path, "cannot select rows");
  check(H5Dread(r.o.table, r.type, mem, space, H5P_DEFAULT, out.data()), r.path,
        "cannot read rows " + std::to_string(start) + ".." + std::to_string(start + count) +
            " (damaged)");
  r.next += count;
  return static_cast<std::int64_t>(count);
}

}  // namespace bkq
