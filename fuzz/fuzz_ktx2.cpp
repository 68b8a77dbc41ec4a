// Fuzz harness: the KTX 2 reader (parse_ktx2, from memory; `shader verify --ibl` reads `bake ibl`'s files
// with it). Contract checked (ktx2_reader.h): an error is one printable line naming the file; a texture it
// accepts has a format of the five it reads, 1 or 6 faces, a level 0 of at least one texel, and each level
// holds exactly faces x height_i x width_i RGBA texels (so texel() reads inside it).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "harness.h"
#include "shadelab/envmap/base/ktx2_reader.h"

using namespace shadelab;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<char> bytes(reinterpret_cast<const char*>(data), reinterpret_cast<const char*>(data) + size);
  const std::string name = "fuzz.ktx2";
  auto t = parse_ktx2(bytes, name);
  if (!t) {
    fuzz::require_one_line(t.error().message, name);
    return 0;
  }
  const std::uint32_t f = t->vk_format;
  if (f != 97 && f != 109 && f != 122 && f != 123 && f != 83) fuzz::finding("an unread format accepted", std::to_string(f));
  if (t->faces != 1 && t->faces != 6) fuzz::finding("faces", std::to_string(t->faces));
  if (t->width < 1 || t->height < 1) fuzz::finding("level 0 size", std::to_string(t->width) + " x " + std::to_string(t->height));
  if (t->faces == 6 && t->width != t->height) fuzz::finding("a cube face that is not square", std::to_string(t->width));
  if (t->levels.empty()) fuzz::finding("no levels", "");
  for (std::size_t l = 0; l < t->levels.size(); ++l) {
    const auto want = static_cast<std::size_t>(t->faces) * static_cast<std::size_t>(t->level_width(static_cast<int>(l))) *
                      static_cast<std::size_t>(t->level_height(static_cast<int>(l))) * 4;
    if (t->levels[l].size() != want) {
      fuzz::finding("level size", std::to_string(l) + ": " + std::to_string(t->levels[l].size()) + " floats, not " + std::to_string(want));
    }
  }
  return 0;
}
