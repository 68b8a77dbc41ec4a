#include "shadelab/brdf/gloss.h"

#include <gtest/gtest.h>

#include <cmath>

namespace shadelab {
namespace {

TEST(Gloss, BlackIsSingleDigitsWhiteIsThousands) {
  const GlossEncoding e;
  EXPECT_DOUBLE_EQ(e.exponent_from_gloss(0.0), 2.0);
  EXPECT_NEAR(e.exponent_from_gloss(1.0), 8192.0, 1e-9);
  EXPECT_LT(e.exponent_from_texel(0), 10.0);
  EXPECT_GE(e.exponent_from_texel(255), 1000.0);
}

TEST(Gloss, EncodingIsLogarithmic) {
  // Equal steps in gloss multiply the exponent by the same factor: n(0.5)^2 = n(0) n(1).
  const GlossEncoding e;
  EXPECT_NEAR(std::pow(e.exponent_from_gloss(0.5), 2), e.exponent_from_gloss(0) * e.exponent_from_gloss(1), 1e-6);
  EXPECT_NEAR(e.exponent_from_gloss(0.25), 2.0 * std::pow(2.0, 3.0), 1e-12);  // 2^(1 + 12/4)
}

TEST(Gloss, RoundTrips) {
  const GlossEncoding e{4.0, 4096.0};
  for (double g : {0.0, 0.1, 0.5, 0.77, 1.0}) EXPECT_NEAR(e.gloss_from_exponent(e.exponent_from_gloss(g)), g, 1e-12);
  for (int t = 0; t < 256; ++t) {
    const auto v = static_cast<std::uint8_t>(t);
    EXPECT_EQ(e.texel_from_exponent(e.exponent_from_texel(v)), v);
  }
  EXPECT_DOUBLE_EQ(e.gloss_from_exponent(1.0), 0.0);      // below the range: clamped
  EXPECT_DOUBLE_EQ(e.gloss_from_exponent(1e7), 1.0);      // above: clamped
}

TEST(Gloss, InvalidEncodingIsAnError) {
  EXPECT_FALSE((GlossEncoding{0.0, 10.0}.validated().has_value()));
  EXPECT_FALSE((GlossEncoding{10.0, 5.0}.validated().has_value()));
  EXPECT_TRUE((GlossEncoding{2.0, 8192.0}.validated().has_value()));
}

}  // namespace
}  // namespace shadelab
