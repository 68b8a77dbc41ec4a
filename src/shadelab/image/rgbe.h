// shadelab Radiance RGBE decoding (.hdr / .pic), from bytes in memory.
//
// Contract: decode_rgbe parses a whole Radiance picture: the "#?" signature, header lines up to the empty
// line (FORMAT must be absent or 32-bit_rle_rgbe; EXPOSURE, PRIMARIES and the rest are ignored: values are
// returned as stored), the resolution line in any of the 8 orientations, and scan lines in any of the three
// encodings (flat, the original run-length pixels, and the per-component run-length encoding), mixed freely.
// A texel (m_r, m_g, m_b, e) decodes to m * 2^(e - 136), and to 0 when e = 0, as Radiance and stb do.
// The result has row 0 at the top. Any truncation, inconsistent length, zero-length run or run beyond the
// scan line is an Error whose message states the reason (without a file name: the caller adds it); the
// decoder never reads past `size` and never loops without consuming input.
//
// Why not stb_image here: stbi_loadf (v2.27) loops forever on a truncated run-length file (a zero count
// read past the end is never consumed), returns garbage without an error for truncated flat files, and does
// not read the original run-length encoding or other orientations (docs/images.md).
#pragma once

#include <cstddef>

#include "shadelab/core/error.h"
#include "shadelab/image/image.h"

namespace shadelab {

// `max_pixels` bounds width * height before anything is allocated.
Result<Image> decode_rgbe(const unsigned char* bytes, std::size_t size, long long max_pixels);

}  // namespace shadelab
