#include "shadelab/analysis/zoo.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shadelab/core/constants.h"

namespace shadelab {
namespace {

constexpr double exponents[] = {0.0, 0.5, 1.0, 2.0, 5.0, 10.0, 100.0, 1000.0, 10000.0};

// The numeric normalization 1 / (2 pi I(n)) equals the closed form taken from the model code.
TEST(Zoo, NumericEqualsClosedFormForEveryRow) {
  for (auto model : zoo_models()) {
    for (double n : exponents) {
      const auto row = zoo_row(model, n);
      ASSERT_TRUE(row) << row.error().message;
      EXPECT_TRUE(row->converged) << model << " n=" << n;
      EXPECT_LE(row->relative_error, 1e-9) << model << " n=" << n << " numeric " << row->numeric << " closed "
                                           << row->closed_form;
      EXPECT_LE(row->numeric_error, 1e-12 * row->numeric) << model << " n=" << n;
    }
  }
}

// Independent closed forms (not from the model code), so a wrong formula in both places is still caught.
double independent_closed_form(std::string_view model, double n) {
  const double p = std::pow(2.0, -n / 2.0);
  if (model == "phong" || model == "blinn-phong-ndf") return (n + 1.0) / (2.0 * pi);
  if (model == "phong-modified" || model == "blinn-phong-heightfield") return (n + 2.0) / (2.0 * pi);
  if (model == "blinn-phong") return (n + 2.0) / (4.0 * pi * (2.0 - p));
  return (n + 2.0) * (n + 4.0) / (8.0 * pi * (p + n));
}

TEST(Zoo, ClosedFormsMatchTheArticle) {
  for (auto model : zoo_models()) {
    for (double n : exponents) {
      const auto row = zoo_row(model, n);
      ASSERT_TRUE(row);
      EXPECT_NEAR(row->closed_form, independent_closed_form(model, n), 1e-14 * row->closed_form) << model;
    }
  }
}

TEST(Zoo, BoundsHoldWhereTheZooGivesThem) {
  for (double n : exponents) {
    for (auto model : {"blinn-phong", "blinn-phong-modified"}) {
      const auto row = zoo_row(model, n);
      ASSERT_TRUE(row);
      ASSERT_TRUE(row->lower && row->upper);
      // The upper bound is attained at n = 0, and blinn-phong's lower bound as n grows (2^(-n/2) underflows
      // to 0 at n = 10000), so equality is allowed up to rounding; the numeric value up to its 1e-12.
      const double slack = 4.0 * 2.2e-16 * row->closed_form;
      EXPECT_LE(*row->lower, row->closed_form + slack) << model << " n=" << n;
      EXPECT_LE(row->closed_form, *row->upper + slack) << model << " n=" << n;
      EXPECT_LE(*row->lower, row->numeric * (1.0 + 1e-12)) << model << " n=" << n;
      EXPECT_LE(row->numeric, *row->upper * (1.0 + 1e-12)) << model << " n=" << n;
    }
    const auto bp = zoo_row("blinn-phong", n);
    EXPECT_NEAR(*bp->lower, (n + 2.0) / (8.0 * pi), 1e-15 * (n + 2.0));
    EXPECT_NEAR(*bp->upper, (n + 4.0) / (8.0 * pi), 1e-15 * (n + 4.0));
    const auto bpm = zoo_row("blinn-phong-modified", n);
    EXPECT_NEAR(*bpm->lower, (n + 6.0) / (8.0 * pi), 1e-15 * (n + 6.0));
    EXPECT_NEAR(*bpm->upper, (n + 8.0) / (8.0 * pi), 1e-15 * (n + 8.0));
  }
  // Strict inside the bounds away from n = 0, as the article writes them.
  const auto row = zoo_row("blinn-phong-modified", 10.0);
  EXPECT_LT(*row->lower, row->closed_form);
  EXPECT_LT(row->closed_form, *row->upper);
  for (auto model : {"phong", "phong-modified", "blinn-phong-ndf", "blinn-phong-heightfield"}) {
    const auto r = zoo_row(model, 10.0);
    EXPECT_FALSE(r->lower || r->upper) << model;
    EXPECT_TRUE(r->lower_text.empty() && r->upper_text.empty()) << model;
  }
}

TEST(Zoo, TextsAndTable) {
  const auto table = zoo_table(50.0);
  ASSERT_TRUE(table);
  ASSERT_EQ(table->size(), 6u);
  EXPECT_EQ((*table)[0].model, "phong");
  EXPECT_EQ((*table)[1].literature, "[3,5,8] Giesen; Lafortune & Willems; Lewis");
  EXPECT_EQ((*table)[2].closed_form_text, "(n+2) / (4 pi (2 - 2^(-n/2)))");
  EXPECT_EQ((*table)[2].lower_text, "(n+2) / (8 pi)");
  EXPECT_EQ((*table)[3].upper_text, "(n+8) / (8 pi)");
  EXPECT_EQ((*table)[3].integrand_text, "cos^n(t/2) cos(t) sin(t)");
  EXPECT_EQ((*table)[4].table, "NDF");
  EXPECT_EQ((*table)[5].integrand_text, "cos^n(a) cos(a) sin(a)");
  for (const auto& r : *table) EXPECT_EQ(r.n, 50.0);
}

TEST(Zoo, RejectsBadInput) {
  EXPECT_FALSE(zoo_row("ward", 10.0));
  EXPECT_NE(zoo_row("ward", 10.0).error().message.find("ward"), std::string::npos);
  EXPECT_FALSE(zoo_row("phong", -1.0));
  EXPECT_FALSE(zoo_row("phong", std::nan("")));
  EXPECT_FALSE(zoo_table(-0.5));
}

}  // namespace
}  // namespace shadelab
