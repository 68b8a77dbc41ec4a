// shadelab images: a plain container of linear RGB float pixels.
//
// Contract: `data` holds width * height * 3 floats, row-major, row 0 at the top, channels R, G, B in that
// order, linear Rec.709 (docs/images.md). Values are radiometric and unbounded (HDR): no clamping, no
// transfer function, no alpha. at() and set() do no bounds checks; x in [0, width), y in [0, height).
// A default-constructed Image is 0 x 0 and empty; file I/O rejects such an image.
#pragma once

#include <algorithm>
#include <cstddef>
#include <new>
#include <vector>

#include "shadelab/color/rgb.h"

namespace shadelab {

// Raw blocks for the allocator below (buffer.cpp): 64-byte aligned; a block of buffer_huge_bytes (2 MiB) or
// more starts on a 2 MiB boundary, is rounded up to whole 2 MiB pages and is advised for transparent huge
// pages (Linux madvise), so that filling it takes one page fault per 2 MiB instead of one per 4 KiB.
inline constexpr std::size_t buffer_huge_bytes = std::size_t{2} << 20;
void* allocate_buffer(std::size_t bytes);
void free_buffer(void* p, std::size_t bytes) noexcept;

// An allocator whose blocks start on a 64-byte boundary (a cache line, an AVX-512 register): so that every
// image row of a size that is a multiple of 16 pixels starts on one too, whatever the heap did before, and
// SIMD kernels read whole lines (a vector load that straddles two lines costs two).
template <class T>
struct CacheLineAllocator {
  using value_type = T;
  CacheLineAllocator() = default;
  template <class U>
  explicit CacheLineAllocator(const CacheLineAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(allocate_buffer(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { free_buffer(p, n * sizeof(T)); }
  template <class U>
  bool operator==(const CacheLineAllocator<U>&) const noexcept {
    return true;
  }
};
using FloatBuffer = std::vector<float, CacheLineAllocator<float>>;

struct Image {
  int width = 0;
  int height = 0;
  FloatBuffer data;  // 3 floats per pixel, row-major, row 0 at the top; 64-byte aligned

  Image() = default;
  // A black image; negative sizes are treated as 0.
  Image(int w, int h)
      : width(std::max(w, 0)),
        height(std::max(h, 0)),
        data(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3, 0.0f) {}

  std::size_t pixel_count() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  bool empty() const { return width <= 0 || height <= 0; }
  // True when data has exactly width * height * 3 floats and both sizes are positive.
  bool is_valid() const { return !empty() && data.size() == pixel_count() * 3; }

  // Index of the first float (R) of pixel (x, y).
  std::size_t index(int x, int y) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
  }
  Rgb at(int x, int y) const {
    const std::size_t i = index(x, y);
    return {static_cast<double>(data[i]), static_cast<double>(data[i + 1]), static_cast<double>(data[i + 2])};
  }
  void set(int x, int y, const Rgb& c) {
    const std::size_t i = index(x, y);
    data[i] = static_cast<float>(c.r);
    data[i + 1] = static_cast<float>(c.g);
    data[i + 2] = static_cast<float>(c.b);
  }
};

}  // namespace shadelab
