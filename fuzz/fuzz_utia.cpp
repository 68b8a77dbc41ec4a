// Fuzz harness: the UTIA .bin BRDF reader (parse_utia, brdf/utia.h). Contract checked: an error is one printable
// line naming the file; a file is accepted only at the format's exact size, with every value finite; evaluating
// and the pdf at a few pairs give finite, non-negative values (the sampler's tables are built only for accepted
// files).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "harness.h"
#include "shadelab/brdf/utia.h"

using namespace shadelab;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string name = "fuzz.bin";
  auto t = parse_utia(std::span<const char>(reinterpret_cast<const char*>(data), size), name);
  if (!t) {
    fuzz::require_one_line(t.error().message, name);
    return 0;
  }
  if (size != UtiaTable::file_bytes) fuzz::finding("a file of the wrong size accepted", std::to_string(size));
  for (double v : t->values) {
    if (!std::isfinite(v)) fuzz::finding("a value not finite accepted", std::to_string(v));
  }
  const UtiaBrdf f(std::make_shared<const UtiaTable>(std::move(*t)));
  const Vec3 dirs[] = {{0.0, 0.0, 1.0}, {0.6, 0.0, 0.8}, {-0.48, 0.6, 0.64}, {0.0, -0.99995, 0.0099995}};
  for (const Vec3& wi : dirs) {
    for (const Vec3& wo : dirs) {
      const Rgb e = f.eval(wi, wo);
      if (!(std::isfinite(e.r) && std::isfinite(e.g) && std::isfinite(e.b)) || e.r < 0.0 || e.g < 0.0 || e.b < 0.0) {
        fuzz::finding("eval not finite or negative", std::to_string(e.r));
      }
      const double p = f.pdf(wi, wo);
      if (!std::isfinite(p) || p < 0.0) fuzz::finding("pdf not finite or negative", std::to_string(p));
    }
  }
  return 0;
}
