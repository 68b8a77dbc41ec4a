#include "shadelab/envmap/diffuse/environment_bakes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace shadelab {
namespace {

TEST(Sh9IrradianceFactors, AreTheCosineBandsInEachConventionTimesTheWindow) {
  // Ramamoorthi & Hanrahan 2001: A_l = pi, 2pi/3, pi/4; the game convention divides by pi.
  const BandFactors radiometric = sh9_irradiance_factors(RadianceUnits::radiometric, ShWindow::none);
  EXPECT_DOUBLE_EQ(radiometric[0], std::acos(-1.0));
  EXPECT_DOUBLE_EQ(radiometric[1], 2.0 * std::acos(-1.0) / 3.0);
  EXPECT_DOUBLE_EQ(radiometric[2], std::acos(-1.0) / 4.0);
  const BandFactors game = sh9_irradiance_factors(RadianceUnits::game, ShWindow::none);
  EXPECT_DOUBLE_EQ(game[0], 1.0);
  EXPECT_DOUBLE_EQ(game[1], 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(game[2], 0.25);
  // Sloan 2008's Hanning window of width 5: (1 + cos(pi l / 5)) / 2.
  const BandFactors hanning = sh9_irradiance_factors(RadianceUnits::game, ShWindow::hanning);
  EXPECT_DOUBLE_EQ(hanning[0], 1.0);
  EXPECT_NEAR(hanning[1], 2.0 / 3.0 * 0.9045084971874737, 1e-15);
  EXPECT_NEAR(hanning[2], 0.25 * 0.6545084971874737, 1e-15);
}

}  // namespace
}  // namespace shadelab
