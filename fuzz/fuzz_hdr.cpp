// Fuzz harness: read_image on Radiance RGBE files (image_harness.h).
#include "image_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return shadelab::fuzz::fuzz_image("hdr", ".hdr", "hdr", data, size);
}
