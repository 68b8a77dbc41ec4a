// brdf_detail::all_unit_directions: the block check of eval_batch_checked (brdf.h), built twice (AVX2 and
// the baseline, chosen at load time by the CPU) so that the AVX2 build vectorizes the stride-3 loads. Each
// |v|^2 is x*x + y*y + z*z in that order, with no contraction (CMAKE_CXX_EXTENSIONS OFF: -ffp-contract=off),
// so the result is is_unit_direction's for every vector, NaN and infinities included (they fail <=).
#include "shadelab/brdf/brdf.h"

namespace shadelab::brdf_detail {

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define SHADELAB_CLONES [[gnu::target_clones("avx2", "default")]]
#else
#define SHADELAB_CLONES
#endif

SHADELAB_CLONES bool all_unit_directions(const Vec3* wi, const Vec3* wo, std::size_t n) {
  constexpr double tol = unit_direction_tolerance;
  int bad = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = wi[i].x * wi[i].x + wi[i].y * wi[i].y + wi[i].z * wi[i].z;
    const double b = wo[i].x * wo[i].x + wo[i].y * wo[i].y + wo[i].z * wo[i].z;
    bad |= static_cast<int>(!(std::abs(a - 1.0) <= tol)) | static_cast<int>(!(std::abs(b - 1.0) <= tol));
  }
  return bad == 0;
}

}  // namespace shadelab::brdf_detail
