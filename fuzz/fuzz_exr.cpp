// Fuzz harness: read_image on OpenEXR files (image_harness.h).
#include "image_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return shadelab::fuzz::fuzz_image("exr", ".exr", "exr", data, size);
}
