// Implementation of the streaming catalogue reader (see catalog_reader.hpp).
#include "io/catalog_reader.hpp"

#include <cmath>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/catalog.hpp"
#include "io/catalog_h5.hpp"
#include "io/csv_util.hpp"
#include "io/input_file.hpp"

namespace bkq {

namespace col = catalog_col;

namespace {

// The columns an HDF5 catalogue is read with, in the order of h5 below.
const std::vector<std::string> kH5Columns = {
    col::event,     col::load,      col::blocks,   col::first_block, col::last_block,
    col::moment,    col::magnitude, col::trigger,  col::duration,    col::trigger_row,
    col::first_row, col::last_row,  col::topplings};

// The largest block or row index a catalogue may hold (far above any chain or lattice).
constexpr std::int64_t kMaxIndex = 1'000'000'000;

}  // namespace

CatalogReader::~CatalogReader() = default;

std::string CatalogReader::where() const {
  return h5_ ? file_ + " row " + std::to_string(events_)
             : file_ + " line " + std::to_string(lineno_);
}

void CatalogReader::check_row(const CatalogEvent& e, const std::string& where) const {
  if (c_load_ >= 0 && !std::isfinite(e.load))
    throw Error(where + ": " + col::load + " (the event's time) must be finite, got " +
                format_real(e.load));
  if (c_duration_ >= 0 && !std::isfinite(e.duration))
    throw Error(where + ": " + col::duration + " must be finite, got " + format_real(e.duration));
  if (c_first_ >= 0 && c_last_ >= 0 && e.first_block > e.last_block)
    throw Error(where + ": " + col::first_block + " = " + std::to_string(e.first_block) +
                " is above " + col::last_block + " = " + std::to_string(e.last_block) +
                "; allowed: first_block <= last_block (the lowest and highest block that "
                "slipped)");
  if (c_first_row_ >= 0 && c_last_row_ >= 0 && e.first_row > e.last_row)
    throw Error(where + ": " + col::first_row + " = " + std::to_string(e.first_row) + " is above " +
                col::last_row + " = " + std::to_string(e.last_row) +
                "; allowed: first_row <= last_row (the lowest and highest row that slipped)");
}

CatalogReader::CatalogReader(const std::filesystem::path& path) : file_(path.string()) {
  if (is_hdf5_file(file_)) {
    h5_ = std::make_unique<CatalogH5Reader>(file_, kH5Columns);
    int* c[] = {&c_event_,     &c_load_,      &c_blocks_,   &c_first_,    &c_last_,
                &c_moment_,    &c_magnitude_, &c_trigger_,  &c_duration_, &c_trigger_row_,
                &c_first_row_, &c_last_row_,  &c_topplings_};
    for (std::size_t k = 0; k < kH5Columns.size(); ++k)
      *c[k] = h5_->has(k) ? static_cast<int>(k) : -1;
    if (c_moment_ < 0 && c_magnitude_ < 0)
      throw Error(file_ + ": missing column '" + col::moment + "'");
    return;
  }
  in_ = open_input(path, "catalogue");
  std::string header_line;
  if (!std::getline(in_, header_line) ||
      header_line.find_first_not_of(" \t\r") == std::string::npos) {
    check_read(in_, path, "catalogue", 0);
    throw Error(file_ + ": empty file, expected a header line");
  }
  const auto header = csv::split(header_line);
  n_fields_ = header.size();
  const Schema& schema = catalog_schema(kEveryCatalogColumn);
  c_event_ = csv::find_column(header, schema, col::event);
  c_load_ = csv::find_column(header, schema, col::load);
  c_blocks_ = csv::find_column(header, schema, col::blocks);
  c_first_ = csv::find_column(header, schema, col::first_block);
  c_last_ = csv::find_column(header, schema, col::last_block);
  c_moment_ = csv::find_column(header, schema, col::moment);
  c_magnitude_ = csv::find_column(header, schema, col::magnitude);
  c_trigger_ = csv::find_column(header, schema, col::trigger);
  c_duration_ = csv::find_column(header, schema, col::duration);
  c_trigger_row_ = csv::find_column(header, schema, col::trigger_row);
  c_first_row_ = csv::find_column(header, schema, col::first_row);
  c_last_row_ = csv::find_column(header, schema, col::last_row);
  c_topplings_ = csv::find_column(header, schema, col::topplings);
  if (c_moment_ < 0 && c_magnitude_ < 0)
    throw Error(file_ + ": missing column '" + col::moment + "' (header: " + header_line + ")");
}

bool CatalogReader::next_h5(CatalogEvent& e) {
  if (block_row_ == block_rows_) {
    block_rows_ = static_cast<std::size_t>(h5_->next_block(block_));
    block_row_ = 0;
    if (block_rows_ == 0) return false;
  }
  const double* v = block_.data() + block_row_++ * kH5Columns.size();
  const std::string where = file_ + " row " + std::to_string(events_ + 1);
  auto as_int = [&](int c, const char* name) -> int {
    if (!(v[c] >= 0 && v[c] <= kMaxIndex))
      throw Error(where + ": " + name + " must be an integer in [0, 1000000000], got " +
                  format_real(v[c]));
    return static_cast<int>(v[c]);
  };
  e = CatalogEvent{};
  e.event = c_event_ >= 0 ? static_cast<std::int64_t>(v[c_event_]) : events_ + 1;
  if (c_load_ >= 0) e.load = v[c_load_];
  if (c_blocks_ >= 0) e.blocks = as_int(c_blocks_, col::blocks);
  if (c_first_ >= 0) e.first_block = as_int(c_first_, col::first_block);
  if (c_last_ >= 0) e.last_block = as_int(c_last_, col::last_block);
  if (c_trigger_ >= 0) e.trigger = as_int(c_trigger_, col::trigger);
  if (c_trigger_row_ >= 0) e.trigger_row = as_int(c_trigger_row_, col::trigger_row);
  if (c_first_row_ >= 0) e.first_row = as_int(c_first_row_, col::first_row);
  if (c_last_row_ >= 0) e.last_row = as_int(c_last_row_, col::last_row);
  if (c_duration_ >= 0) e.duration = v[c_duration_];
  if (c_topplings_ >= 0) e.topplings = as_int(c_topplings_, col::topplings);
  if (c_moment_ >= 0) {
    e.moment = v[c_moment_];
    if (!(e.moment > 0) || !std::isfinite(e.moment))
      throw Error(where + ": " + col::moment + " must be > 0, got " + format_real(e.moment));
    e.magnitude = std::log(e.moment);
  } else {
    e.magnitude = v[c_magnitude_];
    if (!std::isfinite(e.magnitude))
      throw Error(where + ": " + col::magnitude + " must be finite, got " +
                  format_real(e.magnitude));
    e.moment = std::exp(e.magnitude);
  }
  check_row(e, where);
  ++events_;
  return true;
}

bool CatalogReader::next(CatalogEvent& e) {
  if (h5_) return next_h5(e);
  while (std::getline(in_, line_)) {
    ++lineno_;
    if (line_.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string where = file_ + " line " + std::to_string(lineno_);
    // Every row bkquake writes ends in a newline: a last row without one was cut short (its
    // last field may still parse, as another number).
    if (in_.eof() && growing_) break;  // the row its writer is writing now
    if (in_.eof())
      throw Error(where +
                  ": the last row has no line end: the catalogue is cut short "
                  "(truncated); a whole catalogue ends with a newline");
    const auto f = csv::split(line_);
    if (f.size() != n_fields_)
      throw Error(where + ": expected " + std::to_string(n_fields_) + " fields, got " +
                  std::to_string(f.size()));
    auto field = [&](int c) { return f[static_cast<std::size_t>(c)]; };
    auto as_int = [&](int c, const char* name) -> int {
      const std::int64_t v = csv::parse_int(field(c), file_, lineno_, name);
      if (v < 0 || v > kMaxIndex)
        throw Error(where + ": " + name + " must be an integer in [0, 1000000000], got " +
                    std::string(field(c)));
      return static_cast<int>(v);
    };
    e = CatalogEvent{};
    e.event =
        c_event_ >= 0 ? csv::parse_int(field(c_event_), file_, lineno_, col::event) : events_ + 1;
    if (c_load_ >= 0) e.load = csv::parse_double(field(c_load_), file_, lineno_, col::load);
    if (c_blocks_ >= 0) e.blocks = as_int(c_blocks_, col::blocks);
    if (c_first_ >= 0) e.first_block = as_int(c_first_, col::first_block);
    if (c_last_ >= 0) e.last_block = as_int(c_last_, col::last_block);
    if (c_trigger_ >= 0) e.trigger = as_int(c_trigger_, col::trigger);
    if (c_trigger_row_ >= 0) e.trigger_row = as_int(c_trigger_row_, col::trigger_row);
    if (c_first_row_ >= 0) e.first_row = as_int(c_first_row_, col::first_row);
    if (c_last_row_ >= 0) e.last_row = as_int(c_last_row_, col::last_row);
    if (c_duration_ >= 0)
      e.duration = csv::parse_double(field(c_duration_), file_, lineno_, col::duration);
    if (c_topplings_ >= 0) e.topplings = as_int(c_topplings_, col::topplings);
    if (c_moment_ >= 0) {
      e.moment = csv::parse_double(field(c_moment_), file_, lineno_, col::moment);
      if (!(e.moment > 0) || !std::isfinite(e.moment))
        throw Error(where + ": " + col::moment + " must be > 0, got " +
                    std::string(field(c_moment_)));
      e.magnitude = std::log(e.moment);
    } else {
      e.magnitude = csv::parse_double(field(c_magnitude_), file_, lineno_, col::magnitude);
      if (!std::isfinite(e.magnitude))
        throw Error(where + ": " + col::magnitude + " must be finite, got " +
                    std::string(field(c_magnitude_)));
      e.moment = std::exp(e.magnitude);
    }
    check_row(e, where);
    ++events_;
    return true;
  }
  check_read(in_, file_, "catalogue", lineno_);
  return false;
}

void require_events_to_fit(const std::string& file, std::int64_t n) {
  if (n < 2) throw Error(file + ": need at least 2 events to fit, found " + std::to_string(n));
}

}  // namespace bkq
