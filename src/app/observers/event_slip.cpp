// The event-slip writer; see event_slip.hpp.
#include "app/observers/event_slip.hpp"

#include <charconv>
#include <filesystem>
#include <system_error>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/checkpoint.hpp"
#include "io/output.hpp"
#include "io/seismicity_csv.hpp"

namespace bkq {

namespace {
constexpr const char* kState = "event_slip.bytes";
// The longest row: four integers of at most 20 characters, a real and four commas.
constexpr std::size_t kMaxRow = 4 * 20 + kMaxRealChars + 4;
}  // namespace

EventSlipWriter::EventSlipWriter(std::string path, double mu_min, SlipSource source)
    : path_(std::move(path)), mu_min_(mu_min), source_(source) {}

EventSlipWriter::~EventSlipWriter() = default;

// The file as the checkpoint knew it: cut back to the bytes it recorded.
void EventSlipWriter::on_resume(const Checkpoint& c) {
  std::uint64_t bytes = 0;
  if (!find_state(c, kState, bytes))
    throw Error(path_ +
                ": the checkpoint has no event_slip.csv state (the run was started "
                "without output.event_slip; it must keep its scene to resume)");
  std::error_code ec;
  const auto size = std::filesystem::file_size(path_, ec);
  if (ec || size < bytes)
    throw Error(path_ + ": shorter than its checkpoint (" + std::to_string(bytes) +
                " bytes): the file was changed since, and the run cannot resume");
  std::filesystem::resize_file(path_, bytes, ec);
  if (ec) throw Error(path_ + ": cannot cut back to its checkpoint: " + ec.message());
  resumed_ = true;
}

void EventSlipWriter::on_start() {
  const SlipLayout layout{.rows = source_.rows > 1, .topplings = source_.topplings != nullptr};
  file_ = std::make_unique<CsvStream>(path_, header_of(event_slip_schema(layout)), resumed_,
                                      CsvStream::kWhenFull);
}

void EventSlipWriter::on_event(const EventRecord& e) {
  if (!(e.magnitude >= mu_min_)) return;
  // Formatted in place in the file's buffer (as the catalogue's rows are): a map can be
  // thousands of rows per event.
  const auto& slips = *source_.slips;
  const auto integer = [](char* out, long long v) { return std::to_chars(out, out + 20, v).ptr; };
  for (std::size_t k = 0; k < slips.size(); ++k) {
    const auto [j, slip] = slips[k];
    char* const row = file_->begin_row(kMaxRow);
    char* out = integer(row, e.event);
    *out++ = ',';
    if (source_.rows > 1) {
      out = integer(out, j % source_.width);
      *out++ = ',';
      out = integer(out, j / source_.width);
    } else {
      out = integer(out, j);
    }
    *out++ = ',';
    out = format_real_to(out, slip);
    if (source_.topplings) {
      *out++ = ',';
      out = integer(out, (*source_.topplings)[k]);
    }
    file_->end_row(out);
  }
}

void EventSlipWriter::on_phase_end(const Advance&) {
  file_->flush();
}

void EventSlipWriter::on_checkpoint(Checkpoint& c) {
  const std::uint64_t bytes = file_->sync();
  put_state(c, kState, bytes);
}

void EventSlipWriter::on_end(const RunEnd&) {
  file_->close();
}

}  // namespace bkq
