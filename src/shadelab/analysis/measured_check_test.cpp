// `brdf check` through the registry for a measured table (issue 41, section 1): check_brdf("measured", file=...)
// builds it by load_measured_brdf and runs every item, with the tabulated model's numerics (check.cpp, for_model).
// The table is a MERL file the virtual gonioreflectometer wrote of an energy-conserving ggx (no diffuse, f0 0.9),
// so every item that applies passes. The angles are cut to one (30 degrees) and the counts and scans made coarse to
// keep the test short; the CLI runs the full list (docs/models/measured.md: about 80 s).
#include <gtest/gtest.h>

#include <string>

#include "shadelab/analysis/check.h"
#include "shadelab/brdf/merl.h"
#include "shadelab/brdf/test_measured_file.h"

namespace shadelab {
namespace {

TEST(MeasuredCheck, EveryItemPassesThroughTheRegistry) {
  const auto source = make_brdf("ggx", {{"roughness", "0.4"}, {"kd", "0"}, {"f0", "0.9"}});
  ASSERT_TRUE(source.has_value());
  const auto file = testing::write_test_file("ggx_f0.binary", encode_merl(measure_merl(**source)));
  ASSERT_FALSE(file.empty());
  CheckOptions o;
  o.angles_deg = {30.0};
  o.furnace_angles_deg = {30.0};
  o.energy.theta_max_deg = 60.0;
  o.energy.step_deg = 30.0;
  o.energy.theta_tol_deg = 10.0;
  // 50,000 samples in 10 x 20 cells (250 expected each, a noise of 6%): the cells to 1e-2 (the CLI's default check,
  // 1e6 samples in 20 x 40 cells at 3e-3, takes 4.4 s per angle; here 1.2 s)
  o.chi_square.samples = 50'000;
  o.chi_square.cos_theta_bins = 10;
  o.chi_square.phi_bins = 20;
  o.chi_square.cell_rel_tol = 1e-2;
  o.consistency_samples = 20'000;
  const auto report = check_brdf("measured", {{"file", file.string()}}, o);
  ASSERT_TRUE(report.has_value()) << report.error().message;
  for (const auto& item : report->items) EXPECT_TRUE(item.passed) << item.name << ": " << item.detail;
  EXPECT_TRUE(report->passed());
  // The pdf integrates to 1 (the midpoint sum, exact for the table's cells) and reciprocity is rounding.
  ASSERT_NE(report->find("pdf integral"), nullptr);
  EXPECT_LE(report->find("pdf integral")->figure, 1e-6);
  ASSERT_NE(report->find("reciprocity"), nullptr);
  EXPECT_LE(report->find("reciprocity")->figure, 1e-9);
  // A missing file is the registry's one line.
  const auto missing = check_brdf("measured", {{"file", (testing::measured_test_folder().dir() / "none.binary").string()}}, o);
  ASSERT_FALSE(missing.has_value());
  EXPECT_EQ(missing.error().message.rfind("brdf measured: parameter 'file': ", 0), 0u) << missing.error().message;
}

}  // namespace
}  // namespace shadelab
