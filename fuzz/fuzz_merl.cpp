// Fuzz harness: the MERL 100 reader (parse_merl, from memory; the registry's `measured` model reads its `file` with
// read_merl, which checks the size and then calls it). A valid file is 34,992,012 bytes, far beyond what a fuzzer
// makes, so an input is read in one of two ways:
// - as the file itself: anything but 34,992,012 bytes is refused from its size and header alone (nothing read
//   beyond the 12-byte header), so a success is a finding;
// - prefixed "MERLFULL" + a 4-byte little-endian offset: the rest of the input is written at that offset (modulo
//   the planes' size) into the planes of a full-size file of valid header and zero values, which then parses
//   unless a value is NaN or infinite; the error must name the first such value's channel and bin.
// Contract checked (merl.h): an error is one printable line naming the file.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "harness.h"
#include "shadelab/brdf/merl.h"

using namespace shadelab;

namespace {

constexpr std::string_view full_tag = "MERLFULL";

// A full-size file: the header {90, 90, 180}, zero values; the harness restores what each input wrote.
std::vector<char>& full_file() {
  static std::vector<char> bytes = [] {
    std::vector<char> b(MerlTable::file_bytes, '\0');
    const std::int32_t dims[3] = {MerlTable::n_theta_h, MerlTable::n_theta_d, MerlTable::n_phi_d};
    std::memcpy(b.data(), dims, sizeof(dims));
    return b;
  }();
  return bytes;
}

void check_full(std::string_view input, const std::string& name) {
  std::vector<char>& file = full_file();
  const std::size_t planes = MerlTable::file_bytes - 12;
  std::uint32_t offset = 0;
  if (input.size() >= 4) std::memcpy(&offset, input.data(), 4);
  const std::string_view payload = input.size() >= 4 ? input.substr(4) : std::string_view{};
  const std::size_t start = 12 + offset % planes;
  const std::size_t length = std::min(payload.size(), MerlTable::file_bytes - start);
  if (length > 0) std::memcpy(file.data() + start, payload.data(), length);  // an empty view may hold a null pointer
  // The first value that is not finite, as the parser must name it.
  std::size_t first_bad = MerlTable::count * 3;
  for (std::size_t v = (start - 12) / 8; v * 8 + 12 < start + length; ++v) {
    double d = 0.0;
    std::memcpy(&d, file.data() + 12 + v * 8, 8);
    if (!std::isfinite(d)) {
      first_bad = v;
      break;
    }
  }
  auto t = parse_merl(file, name);
  if (t) {
    if (first_bad != MerlTable::count * 3) fuzz::finding("a value that is not finite accepted", std::to_string(first_bad));
    if (t->stored.size() != 3 * MerlTable::count) fuzz::finding("plane size", std::to_string(t->stored.size()));
    if (std::memcmp(t->stored.data(), file.data() + 12, planes) != 0) fuzz::finding("values", "not the file's bytes");
  } else {
    fuzz::require_one_line(t.error().message, name);
    if (first_bad == MerlTable::count * 3) fuzz::finding("a finite file refused", t.error().message);
    const std::size_t bin = first_bad % MerlTable::count;
    const std::string where = std::string("channel ") + "RGB"[first_bad / MerlTable::count] + " at bin (theta_h " +
                              std::to_string(bin / (MerlTable::n_theta_d * MerlTable::n_phi_d)) + ", theta_d " +
                              std::to_string((bin / MerlTable::n_phi_d) % MerlTable::n_theta_d) + ", phi_d " +
                              std::to_string(bin % MerlTable::n_phi_d) + ")";
    if (t.error().message.find(where) == std::string::npos) fuzz::finding("the value named", t.error().message + " (expected " + where + ")");
  }
  std::memset(file.data() + start, 0, length);  // back to zeros for the next input
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::string name = "fuzz.binary";
  if (input.substr(0, full_tag.size()) == full_tag) {
    check_full(input.substr(full_tag.size()), name);
    return 0;
  }
  auto t = parse_merl(std::span<const char>(input.data(), input.size()), name);
  if (t) {
    if (size != MerlTable::file_bytes) fuzz::finding("a file of the wrong size accepted", std::to_string(size));
    return 0;
  }
  fuzz::require_one_line(t.error().message, name);
  return 0;
}
