// shadelab deterministic quadrature: it lives in the numeric module (numeric/quadrature.h), below brdf, so
// that the kernels' energy tables can use it; this header keeps analysis' include path working.
#pragma once

#include "shadelab/numeric/quadrature.h"
