// shadelab bake progress: the callback the long bakes (irradiance, the Phong and GGX chains) call on the
// calling thread between blocks of work, with the fraction done in [0, 1].
#pragma once

#include <functional>

namespace shadelab {

using ProgressFn = std::function<void(double fraction_done)>;

}  // namespace shadelab
