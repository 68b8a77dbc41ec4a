// The image harnesses' shared body (fuzz_exr.cpp, fuzz_hdr.cpp, fuzz_png.cpp): the input is written as
// image<extension> and read with read_image. Contract checked (image_io.h): an error is one printable line
// naming the file; an image is valid, within max_image_side and max_image_pixels, every value finite (NaN
// and Inf are repaired and counted), and ReadInfo names the format.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "harness.h"
#include "shadelab/image/image_io.h"

namespace shadelab::fuzz {

inline int fuzz_image(const char* name, const char* extension, const char* format, const std::uint8_t* data,
                      std::size_t size) {
  static const std::filesystem::path file = work_dir(name) / (std::string("image") + extension);
  write_file(file, as_text(data, size));
  ReadInfo info;
  auto image = read_image(file, &info);
  if (!image) {
    require_one_line(image.error().message, file.string());
    return 0;
  }
  if (!image->is_valid()) finding("invalid image", std::to_string(image->width) + " x " + std::to_string(image->height));
  if (image->width > max_image_side || image->height > max_image_side ||
      static_cast<long long>(image->pixel_count()) > max_image_pixels) {
    finding("image beyond the size limits", std::to_string(image->width) + " x " + std::to_string(image->height));
  }
  for (float v : image->data) {
    if (!std::isfinite(v)) finding("non-finite value in a read image", "");
  }
  if (info.format != format) finding("wrong format in ReadInfo", info.format);
  return 0;
}

}  // namespace shadelab::fuzz
