// Fuzz harness: read_image on PNG files (image_harness.h).
#include "image_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return shadelab::fuzz::fuzz_image("png", ".png", "png", data, size);
}
