// Fuzz harness: the RGL/EPFL tensor .bsdf reader (parse_rgl, brdf/rgl.h). Contract checked: an error is one
// printable line naming the file; a file it accepts has every field inside the file's bytes, the BRDF's tables
// consistent (theta_i and phi_i increasing), and evaluating, sampling and the pdf at a few pairs give finite,
// non-negative values.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "harness.h"
#include "shadelab/brdf/rgl.h"

using namespace shadelab;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string name = "fuzz.bsdf";
  std::vector<char> bytes(reinterpret_cast<const char*>(data), reinterpret_cast<const char*>(data) + size);
  auto container = parse_tensor_file(bytes, name);
  if (!container) {
    fuzz::require_one_line(container.error().message, name);
  } else {
    for (const auto& f : container->fields) {
      const std::size_t bytes_of = f.count * tensor_dtype_size(f.dtype);
      if (f.offset > size || bytes_of > size - f.offset) fuzz::finding("a field outside the file", f.name);
    }
  }
  auto t = parse_rgl(std::move(bytes), name);
  if (!t) {
    fuzz::require_one_line(t.error().message, name);
    return 0;
  }
  for (std::size_t i = 0; i + 1 < t->theta_i.size(); ++i) {
    if (!(t->theta_i[i + 1] > t->theta_i[i])) fuzz::finding("theta_i not increasing", std::to_string(i));
  }
  const RglBrdf f(std::make_shared<const RglTable>(std::move(*t)));
  const Vec3 dirs[] = {{0.0, 0.0, 1.0}, {0.6, 0.0, 0.8}, {-0.48, 0.6, 0.64}, {0.0, -0.99995, 0.0099995}};
  for (const Vec3& wi : dirs) {
    for (const Vec3& wo : dirs) {
      const Rgb e = f.eval(wi, wo);
      if (!(std::isfinite(e.r) && std::isfinite(e.g) && std::isfinite(e.b)) || e.r < 0.0 || e.g < 0.0 || e.b < 0.0) {
        fuzz::finding("eval not finite or negative", std::to_string(e.r) + " " + std::to_string(e.g) + " " + std::to_string(e.b));
      }
      const double p = f.pdf(wi, wo);
      if (!std::isfinite(p) || p < 0.0) fuzz::finding("pdf not finite or negative", std::to_string(p));
    }
    const BrdfSample s = f.sample(wi, {0.3, 0.7}, 0.5);
    if (!std::isfinite(s.pdf) || s.pdf < 0.0 || !std::isfinite(s.weight.r)) fuzz::finding("sample not finite", std::to_string(s.pdf));
  }
  return 0;
}
