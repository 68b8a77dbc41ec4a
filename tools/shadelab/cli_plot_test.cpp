// End-to-end tests of `shadelab plot` and `shadelab sheet`: run the built binary, check the data it prints
// (--json) and writes (--csv) against the analysis and BRDF libraries computed here in the test process,
// the chart files (PNG signature and IHDR size, SVG well-formed with the requested size), and the errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "shadelab/analysis/albedo.h"
#include "shadelab/analysis/zoo.h"
#include "shadelab/brdf/fresnel.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/image/image_io.h"

namespace {

using shadelab::testing::CliRun;
using shadelab::testing::expect_usage_error;
using shadelab::testing::json_of;
using shadelab::testing::run;
namespace fs = std::filesystem;

std::string temp_dir() {
  static const std::string dir = shadelab::testing::process_temp_dir("shadelab_cli_plot").string() + "/";
  return dir;
}

std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Width and height from a PNG's IHDR chunk, after checking the 8-byte signature; {-1, -1} if not a PNG.
std::pair<int, int> png_size(const std::string& bytes) {
  const std::string signature = "\x89PNG\r\n\x1a\n";
  if (bytes.size() < 24 || bytes.compare(0, 8, signature) != 0 || bytes.compare(12, 4, "IHDR") != 0) return {-1, -1};
  const auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
    return static_cast<int>(v);
  };
  return {be32(16), be32(20)};
}

// A small well-formedness check: every element closed in order, attributes quoted; comments, processing
// instructions and CDATA skipped. Returns "" or what is wrong.
std::string xml_problem(const std::string& s) {
  std::vector<std::string> open;
  std::size_t i = 0;
  bool root_seen = false;
  while ((i = s.find('<', i)) != std::string::npos) {
    if (s.compare(i, 4, "<!--") == 0) {
      i = s.find("-->", i);
      if (i == std::string::npos) return "unterminated comment";
      continue;
    }
    if (s.compare(i, 9, "<![CDATA[") == 0) {
      i = s.find("]]>", i);
      if (i == std::string::npos) return "unterminated CDATA";
      continue;
    }
    if (s.compare(i, 2, "<?") == 0 || s.compare(i, 2, "<!") == 0) {
      i = s.find('>', i);
      if (i == std::string::npos) return "unterminated declaration";
      continue;
    }
    // Find the end of the tag, skipping quoted attribute values.
    std::size_t j = i + 1;
    char quote = 0;
    for (; j < s.size(); ++j) {
      if (quote != 0) {
        if (s[j] == quote) quote = 0;
      } else if (s[j] == '"' || s[j] == '\'') {
        quote = s[j];
      } else if (s[j] == '>') {
        break;
      }
    }
    if (j >= s.size()) return "unterminated tag at " + std::to_string(i);
    const std::string tag = s.substr(i + 1, j - i - 1);
    if (tag.empty()) return "empty tag";
    if (tag[0] == '/') {
      const std::string name = tag.substr(1, tag.find_first_of(" \t\n") - 1);
      if (open.empty() || open.back() != name)
        return "</" + name + "> does not close <" + (open.empty() ? "" : open.back()) + ">";
      open.pop_back();
    } else {
      const std::string name = tag.substr(0, tag.find_first_of(" \t\n/"));
      if (open.empty() && root_seen) return "a second root element <" + name + ">";
      root_seen = true;
      if (tag.back() != '/') open.push_back(name);
    }
    i = j + 1;
  }
  if (!open.empty()) return "<" + open.back() + "> is not closed";
  return root_seen ? "" : "no element";
}

void expect_svg(const std::string& path, int width, int height) {
  const std::string svg = read_file(path);
  ASSERT_FALSE(svg.empty()) << path;
  EXPECT_EQ(xml_problem(svg), "") << path;
  const auto root = svg.find("<svg");
  ASSERT_NE(root, std::string::npos) << path;
  const std::string tag = svg.substr(root, svg.find('>', root) - root);
  EXPECT_NE(tag.find("width=\"" + std::to_string(width) + "px\""), std::string::npos) << tag;
  EXPECT_NE(tag.find("height=\"" + std::to_string(height) + "px\""), std::string::npos) << tag;
  EXPECT_NE(tag.find("viewBox=\"0 0 " + std::to_string(width) + " " + std::to_string(height) + "\""), std::string::npos)
      << tag;
}

void expect_png(const std::string& path, int width, int height) {
  const auto [w, h] = png_size(read_file(path));
  EXPECT_EQ(w, width) << path;
  EXPECT_EQ(h, height) << path;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string line; std::getline(ss, line);) out.push_back(line);
  return out;
}

// Splits a CSV line (RFC 4180 quoting).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        out.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

shadelab::BrdfPtr brdf(const std::string& model, const shadelab::ParamAssignments& params) {
  auto f = shadelab::make_brdf(model, params);
  EXPECT_TRUE(f.has_value()) << (f ? "" : f.error().message);
  return std::move(f).value();
}

shadelab::Vec3 plane_dir(double deg) {
  const double a = deg * shadelab::pi / 180.0;
  return {std::sin(a), 0.0, std::cos(a)};
}

void expect_rel(double got, double want, double tol, const std::string& what) {
  EXPECT_LE(std::abs(got - want), tol * std::max(std::abs(want), 1e-300))
      << what << ": got " << got << ", want " << want;
}

TEST(CliPlot, HelpForEverySubcommand) {
  for (const char* c :
       {"plot --help", "plot lobe --help", "plot albedo --help", "plot fv --help", "plot zoo --help", "sheet --help"}) {
    const CliRun r = run(c);
    EXPECT_EQ(r.code, 0) << c;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << c;
  }
}

TEST(CliPlot, LobeDataIsTheBrdfInThePlaneOfIncidence) {
  const std::string dir = temp_dir();
  const std::string svg = dir + "lobe.svg";
  const std::string csv = dir + "lobe.csv";
  const auto j =
      json_of(run("plot lobe phong cook-torrance --param kd=0.1 --param phong:n=80 --param 2:f0=0.5 "
                  "--theta-in 30 --samples 181 --size 640x480 --out " +
                  svg + " --csv " + csv + " --json"));
  expect_svg(svg, 640, 480);
  ASSERT_EQ(j["series"].size(), 2u);
  EXPECT_EQ(j["fixed"], "light");
  EXPECT_EQ(j["quantity"], "f");
  EXPECT_EQ(j["series"][0]["label"], "phong (kd=0.1, n=80)");
  EXPECT_EQ(j["series"][1]["label"], "cook-torrance (kd=0.1, f0=0.5)");
  std::vector<shadelab::BrdfPtr> models;
  models.push_back(brdf("phong", {{"kd", "0.1"}, {"n", "80"}}));
  models.push_back(brdf("cook-torrance", {{"kd", "0.1"}, {"f0", "0.5"}}));
  const shadelab::Vec3 wi = plane_dir(-30.0);  // the light on the left, the mirror direction at +30
  for (std::size_t m = 0; m < 2; ++m) {
    const auto& s = j["series"][m];
    ASSERT_EQ(s["angle_deg"].size(), 181u);
    EXPECT_EQ(s["angle_deg"][0].get<double>(), -90.0);
    EXPECT_EQ(s["angle_deg"][180].get<double>(), 90.0);
    EXPECT_EQ(s["rgb"][0][0].get<double>(), 0.0);  // on the horizon
    EXPECT_EQ(s["rgb"][180][0].get<double>(), 0.0);
    for (std::size_t i = 1; i < 180; i += 7) {
      const double a = s["angle_deg"][i].get<double>();
      EXPECT_NEAR(a, -90.0 + static_cast<double>(i), 1e-12);
      const shadelab::Rgb want = models[m]->eval(wi, plane_dir(a));
      for (int c = 0; c < 3; ++c)
        expect_rel(s["rgb"][i][c].get<double>(), want[c], 1e-12, "rgb at " + std::to_string(a));
      expect_rel(s["luminance"][i].get<double>(), shadelab::luminance(want), 1e-12, "luminance");
      expect_rel(s["plotted"][i].get<double>(), shadelab::luminance(want), 1e-12, "plotted");
    }
  }
  // The phong lobe peaks at the mirror direction (+30 degrees).
  const auto& lum = j["series"][0]["luminance"];
  std::size_t best = 0;
  for (std::size_t i = 0; i < lum.size(); ++i) {
    if (lum[i].get<double>() > lum[best].get<double>()) best = i;
  }
  EXPECT_EQ(j["series"][0]["angle_deg"][best].get<double>(), 30.0);

  // The CSV holds the same numbers, one row per model and angle.
  const auto rows = lines_of(read_file(csv));
  ASSERT_EQ(rows.size(), 1u + 2u * 181u);
  EXPECT_EQ(rows[0], "model,params,label,angle_deg,r,g,b,luminance,plotted");
  for (std::size_t k : {1u, 100u, 182u, 300u}) {
    const auto f = csv_fields(rows[k]);
    ASSERT_EQ(f.size(), 9u) << rows[k];
    const std::size_t m = k <= 181 ? 0 : 1;
    const std::size_t i = (k - 1) % 181;
    EXPECT_EQ(f[0], m == 0 ? "phong" : "cook-torrance");
    EXPECT_EQ(std::stod(f[3]), j["series"][m]["angle_deg"][i].get<double>());
    EXPECT_EQ(std::stod(f[4]), j["series"][m]["rgb"][i][0].get<double>());
    EXPECT_EQ(std::stod(f[7]), j["series"][m]["luminance"][i].get<double>());
  }
}

TEST(CliPlot, ParametersForSeveralModels) {
  const std::string out = " --samples 3 --out " + temp_dir() + "params.svg --json";
  // NAME=VALUE goes to every model that declares NAME; a later assignment replaces an earlier one; K: picks
  // one of two models of the same name; MODELs may come after --param.
  const auto j =
      json_of(run("plot lobe --param n=10 phong lambert phong --param kd=0.2 --param 3:n=100 "
                  "--param phong:ks=0.3" +
                  out));
  ASSERT_EQ(j["series"].size(), 3u);
  EXPECT_EQ(j["series"][0]["label"], "phong (n=10, kd=0.2, ks=0.3)");
  EXPECT_EQ(j["series"][1]["label"], "lambert (kd=0.2)");
  EXPECT_EQ(j["series"][2]["label"], "phong (n=100, kd=0.2, ks=0.3)");
  EXPECT_EQ(j["series"][2]["params"]["n"], "100");
  // The value at the normal is the model's: phong with n = 100, kd = 0.2, ks = 0.3 for the third series.
  const auto f = brdf("phong", {{"n", "100"}, {"kd", "0.2"}, {"ks", "0.3"}});
  expect_rel(j["series"][2]["rgb"][1][0].get<double>(), f->eval(plane_dir(-45.0), plane_dir(0.0)).r, 1e-12, "phong 3");
  const auto a = json_of(run("plot albedo --theta 0 --theta 30 lambert --out " + temp_dir() + "params2.svg --json"));
  EXPECT_EQ(a["series"][0]["theta_deg"].size(), 2u);
}

TEST(CliPlot, LobeWithCosineAndFixedViewer) {
  const std::string out = temp_dir() + "lobe_viewer.png";
  const auto j =
      json_of(run("plot lobe blinn-phong --param n=20 --fixed viewer --cos --log --channel max "
                  "--theta-in 60 --samples 37 --size 400x300 --out " +
                  out + " --json"));
  expect_png(out, 400, 300);
  EXPECT_EQ(j["fixed"], "viewer");
  EXPECT_EQ(j["quantity"], "f_cos");
  EXPECT_EQ(j["channel"], "max");
  const auto f = brdf("blinn-phong", {{"n", "20"}});
  const shadelab::Vec3 wo = plane_dir(-60.0);
  const auto& s = j["series"][0];
  for (std::size_t i = 1; i + 1 < 37; ++i) {
    const double a = s["angle_deg"][i].get<double>();
    const shadelab::Vec3 wi = plane_dir(a);
    // The light is swept: f(wi(a), wo) cos(a), which is not f(wo, wi(a)) cos(a) for this non-reciprocal form.
    const shadelab::Rgb want = f->eval(wi, wo) * wi.z;
    expect_rel(s["rgb"][i][0].get<double>(), want.r, 1e-12, "f cos at " + std::to_string(a));
    expect_rel(s["plotted"][i].get<double>(), want.max_component(), 1e-12, "max channel");
  }
}

TEST(CliPlot, AlbedoDataIsDirectionalAlbedo) {
  const std::string dir = temp_dir();
  const std::string png = dir + "albedo.png";
  const std::string csv = dir + "albedo.csv";
  const auto j =
      json_of(run("plot albedo lambert minimalist-cook-torrance --param kd=0.5 --param 2:kd=0 "
                  "--param 2:ks=0.05 --theta 0 --theta 45 --theta 85 --size 300x200 --out " +
                  png + " --csv " + csv + " --json"));
  expect_png(png, 300, 200);
  ASSERT_EQ(j["series"].size(), 2u);
  std::vector<shadelab::BrdfPtr> models;
  models.push_back(brdf("lambert", {{"kd", "0.5"}}));
  models.push_back(brdf("minimalist-cook-torrance", {{"kd", "0"}, {"ks", "0.05"}}));
  shadelab::AlbedoOptions options;
  options.quadrature.rel_tol = 1e-8;
  const std::vector<double> thetas = {0.0, 45.0, 85.0};
  for (std::size_t m = 0; m < 2; ++m) {
    const auto& s = j["series"][m];
    ASSERT_EQ(s["theta_deg"].size(), 3u);
    EXPECT_TRUE(s["converged"].get<bool>());
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(s["theta_deg"][i].get<double>(), thetas[i]);
      const shadelab::Rgb want =
          shadelab::directional_albedo(*models[m], shadelab::deg_to_rad(thetas[i]), options).albedo;
      for (int c = 0; c < 3; ++c) expect_rel(s["rgb"][i][c].get<double>(), want[c], 1e-12, "albedo");
      expect_rel(s["plotted"][i].get<double>(), want.max_component(), 1e-12, "largest channel");
    }
  }
  // Lambert's albedo is kd at every angle.
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(j["series"][0]["rgb"][i][0].get<double>(), 0.5, 1e-8);
  // The minimalist model's albedo grows toward grazing (its 1/(L.H)^3).
  EXPECT_GT(j["series"][1]["plotted"][2].get<double>(), j["series"][1]["plotted"][0].get<double>());
  const auto rows = lines_of(read_file(csv));
  ASSERT_EQ(rows.size(), 7u);
  EXPECT_EQ(rows[0], "model,params,label,theta_deg,r,g,b,luminance,plotted,converged");
  EXPECT_EQ(csv_fields(rows[4])[0], "minimalist-cook-torrance");
  EXPECT_EQ(std::stod(csv_fields(rows[6])[8]), j["series"][1]["plotted"][2].get<double>());
}

TEST(CliPlot, FvCurvesAreTheArticlesTerms) {
  const std::string dir = temp_dir();
  const std::string svg = dir + "fv.svg";
  const std::string csv = dir + "fv.csv";
  const auto j = json_of(run("plot fv --samples 18 --max-angle 85 --out " + svg + " --csv " + csv + " --json"));
  expect_svg(svg, 800, 600);
  ASSERT_EQ(j["curves"].size(), 3u);
  const std::vector<double> f0s = {0.02, 0.05, 0.8};  // the zoo article's figure
  for (std::size_t k = 0; k < 3; ++k) {
    const auto& c = j["curves"][k];
    EXPECT_EQ(c["f0"].get<double>(), f0s[k]);
    ASSERT_EQ(c["angle_deg"].size(), 18u);
    EXPECT_EQ(c["angle_deg"][17].get<double>(), 85.0);
    for (std::size_t i = 0; i < 18; ++i) {
      const double lh = std::cos(c["angle_deg"][i].get<double>() * shadelab::pi / 180.0);
      expect_rel(c["l_dot_h"][i].get<double>(), lh, 1e-15, "L.H");
      expect_rel(c["minimalist"][i].get<double>(), f0s[k] / (4.0 * lh * lh * lh), 1e-13, "minimalist");
      expect_rel(c["schlick_kelemen"][i].get<double>(), shadelab::F_schlick(lh, f0s[k]) * shadelab::V_kelemen(lh),
                 1e-13, "schlick x kelemen");
    }
    // At L.H = 1 both are F0 / 4.
    EXPECT_DOUBLE_EQ(c["minimalist"][0].get<double>(), f0s[k] / 4.0);
    EXPECT_DOUBLE_EQ(c["schlick_kelemen"][0].get<double>(), f0s[k] / 4.0);
  }
  // The article: the minimalist term underestimates grazing reflectance for low F0 and overestimates it for
  // metals (F0 = 0.8).
  EXPECT_LT(j["curves"][0]["minimalist"][17].get<double>(), j["curves"][0]["schlick_kelemen"][17].get<double>());
  EXPECT_GT(j["curves"][2]["minimalist"][17].get<double>(), j["curves"][2]["schlick_kelemen"][17].get<double>());
  EXPECT_EQ(lines_of(read_file(csv)).size(), 1u + 3u * 18u);
}

TEST(CliPlot, FvCurvesAreWhatTheModelsMultiplyDBy) {
  // docs: minimalist-cook-torrance with ks = F0 is D_ndf x minimalist, and cook-torrance with Schlick F,
  // Kelemen V and Blinn-Phong D is D x schlick_kelemen. Checked on one reflection pair per F0.
  const shadelab::Vec3 wi = shadelab::normalize(shadelab::Vec3{-0.7, 0.2, 0.5});
  const shadelab::Vec3 wo = shadelab::normalize(shadelab::Vec3{0.4, 0.1, 0.6});
  const shadelab::Vec3 h = shadelab::normalize(wi + wo);
  const double lh = shadelab::dot(wi, h);
  std::ostringstream angle;
  angle.precision(17);
  angle << std::acos(lh) * 180.0 / shadelab::pi;
  const auto j = json_of(
      run("plot fv --f0 0.3 --max-angle " + angle.str() + " --samples 2 --out " + temp_dir() + "fv1.svg --json"));
  const double minimalist = j["curves"][0]["minimalist"][1].get<double>();
  const double schlick = j["curves"][0]["schlick_kelemen"][1].get<double>();
  const auto mct = brdf("minimalist-cook-torrance", {{"kd", "0"}, {"ks", "0.3"}, {"n", "30"}});
  expect_rel(mct->eval(wi, wo).r, shadelab::D_blinn_phong_ndf(h.z, 30.0) * minimalist, 1e-10, "minimalist BRDF");
  const auto ct = brdf(
      "cook-torrance",
      {{"kd", "0"}, {"ks", "1"}, {"d", "blinn-phong"}, {"n", "30"}, {"g", "kelemen"}, {"f", "schlick"}, {"f0", "0.3"}});
  expect_rel(ct->eval(wi, wo).r, shadelab::D_blinn_phong(h.z, 30.0) * schlick, 1e-10, "cook-torrance BRDF");
}

TEST(CliPlot, ZooCurvesAreTheZooClosedFormsAndBounds) {
  const std::string dir = temp_dir();
  const std::string png = dir + "zoo.png";
  const std::string csv = dir + "zoo.csv";
  const auto j = json_of(
      run("plot zoo --samples 9 --n-min 0.5 --n-max 5000 --size 1000x700 --out " + png + " --csv " + csv + " --json"));
  expect_png(png, 1000, 700);
  ASSERT_EQ(j["rows"].size(), 6u);
  std::size_t with_bounds = 0;
  for (std::size_t k = 0; k < 6; ++k) {
    const auto& r = j["rows"][k];
    EXPECT_EQ(r["model"].get<std::string>(), std::string(shadelab::zoo_models()[k]));
    ASSERT_EQ(r["n"].size(), 9u);
    EXPECT_EQ(r["n"][0].get<double>(), 0.5);
    EXPECT_EQ(r["n"][8].get<double>(), 5000.0);
    for (std::size_t i = 0; i < 9; ++i) {
      const double n = r["n"][i].get<double>();
      if (i > 0) expect_rel(n / r["n"][i - 1].get<double>(), std::pow(1e4, 1.0 / 8.0), 1e-12, "log spacing");
      const auto row = shadelab::zoo_row(r["model"].get<std::string>(), n);
      ASSERT_TRUE(row.has_value());
      EXPECT_EQ(r["closed_form"][i].get<double>(), row->closed_form);
      // The closed form is the normalization the quadrature finds.
      expect_rel(r["closed_form"][i].get<double>(), row->numeric, 1e-9, r["model"].get<std::string>());
      if (row->lower) {
        EXPECT_EQ(r["lower"][i].get<double>(), *row->lower);
        EXPECT_EQ(r["upper"][i].get<double>(), *row->upper);
        EXPECT_LE(*row->lower, row->closed_form);
        EXPECT_GE(*row->upper, row->closed_form);
      } else {
        EXPECT_TRUE(r["lower"].is_null());
      }
    }
    with_bounds += r["lower"].is_null() ? 0 : 1;
  }
  EXPECT_EQ(with_bounds, 2u);
  EXPECT_EQ(lines_of(read_file(csv)).size(), 1u + 6u * 9u);

  const std::string svg = dir + "zoo_rel.svg";
  const auto rel = json_of(run("plot zoo --relative --row blinn-phong --samples 5 --out " + svg + " --json"));
  expect_svg(svg, 800, 600);
  EXPECT_TRUE(rel["relative"].get<bool>());
  ASSERT_EQ(rel["rows"].size(), 1u);
}

TEST(CliPlot, SameInputSameBytes) {
  const std::string dir = temp_dir();
  for (const char* ext : {".svg", ".png"}) {
    const std::string a = dir + "same_a" + ext;
    const std::string b = dir + "same_b" + ext;
    ASSERT_EQ(run("plot lobe phong-modified --samples 91 --out " + a).code, 0);
    ASSERT_EQ(run("plot lobe phong-modified --samples 91 --out " + b).code, 0);
    EXPECT_EQ(read_file(a), read_file(b)) << ext;
  }
}

TEST(CliPlot, SheetLayoutAndPixels) {
  const std::string dir = temp_dir();
  const std::string png = dir + "sheet.png";
  const std::string exr = dir + "sheet.exr";
  const std::string csv = dir + "sheet.csv";
  const auto j =
      json_of(run("sheet phong-modified blinn-phong-modified --param kd=0.3 --vary n=10,1000 --cell 16 "
                  "--spp 2 --light directional --out " +
                  png + " --exr " + exr + " --csv " + csv + " --json"));
  // 2 x 2 cells of 16 px with a gap of 2 px between and around them.
  EXPECT_EQ(j["gap"].get<int>(), 2);
  EXPECT_EQ(j["width"].get<int>(), 38);
  EXPECT_EQ(j["height"].get<int>(), 38);
  expect_png(png, 38, 38);
  ASSERT_EQ(j["cells"].size(), 4u);
  EXPECT_EQ(j["cells"][3]["model"], "blinn-phong-modified");
  EXPECT_EQ(j["cells"][3]["params"]["n"], "1000");
  EXPECT_EQ(j["cells"][3]["params"]["kd"], "0.3");
  EXPECT_EQ(j["cells"][3]["x"].get<int>(), 20);
  EXPECT_EQ(j["cells"][3]["y"].get<int>(), 20);
  EXPECT_EQ(lines_of(read_file(csv)).size(), 5u);
  auto image = shadelab::read_image(exr);
  ASSERT_TRUE(image.has_value()) << image.error().message;
  ASSERT_EQ(image->width, 38);
  for (const auto& c : j["cells"]) {
    const int x = c["x"].get<int>();
    const int y = c["y"].get<int>();
    // The sphere's centre faces the camera and the light is in front: lit. The cell's corner is background.
    EXPECT_GT(image->at(x + 8, y + 8).g, 0.05) << c["label"];
    EXPECT_EQ(image->at(x, y).g, 0.0) << c["label"];
  }
  EXPECT_EQ(image->at(0, 0).g, 0.0);  // the gap, black in the EXR
}

TEST(CliPlot, SheetUnderAUniformHdriIsAWhiteFurnace) {
  // A white Lambert sphere in a uniform environment of radiance 0.5 shows 0.5 everywhere (it cannot see itself).
  const std::string dir = temp_dir();
  const std::string env_path = dir + "uniform.exr";
  shadelab::Image env(16, 8);
  for (float& v : env.data) v = 0.5f;
  ASSERT_TRUE(shadelab::write_image(env, env_path).has_value());
  const std::string exr = dir + "furnace.exr";
  ASSERT_EQ(run("sheet lambert --param kd=1 --hdri " + env_path + " --cell 16 --spp 16 --out " + dir +
                "furnace.png --exr " + exr)
                .code,
            0);
  auto image = shadelab::read_image(exr);
  ASSERT_TRUE(image.has_value());
  // Background pixels see the map directly: exactly 0.5. On the sphere the estimate is unbiased but noisy
  // (MIS of cosine and environment sampling), so the cell's mean is checked tightly and each pixel loosely.
  EXPECT_EQ(image->at(2, 2).r, 0.5f);
  EXPECT_EQ(image->at(17, 17).r, 0.5f);
  double sum = 0.0;
  double worst = 0.0;
  for (int y = 2; y < 18; ++y) {
    for (int x = 2; x < 18; ++x) {
      sum += image->at(x, y).r;
      worst = std::max(worst, std::abs(image->at(x, y).r - 0.5));
    }
  }
  EXPECT_NEAR(sum / 256.0, 0.5, 0.005);
  EXPECT_LT(worst, 0.2);  // 16 spp: about 0.07 seen
}

TEST(CliPlot, BadInput) {
  const std::string dir = temp_dir();
  const std::string out = " --out " + dir + "bad.svg";
  expect_usage_error("plot lobe nosuchmodel" + out, "unknown BRDF model 'nosuchmodel'");
  expect_usage_error("plot lobe phong --param shininess=3" + out, "unknown parameter 'shininess'");
  expect_usage_error("plot lobe phong --param n=-1" + out, "parameter 'n' = -1 is out of range");
  expect_usage_error("plot lobe phong lambert --param shininess=3" + out, "has a parameter 'shininess'");
  expect_usage_error("plot lobe phong lambert --param ward:n=3" + out, "'ward' is not one of the models given");
  expect_usage_error("plot lobe phong lambert --param 3:n=3" + out, "model number 3 is out of range [1, 2]");
  expect_usage_error("plot lobe phong --param n" + out, "NAME=VALUE");
  expect_usage_error("plot lobe phong --theta-in 90" + out, "--theta-in: 90 is out of range");
  expect_usage_error("plot lobe phong --theta-in -1" + out, "--theta-in");
  expect_usage_error("plot lobe phong --fixed camera" + out, "--fixed");
  expect_usage_error("plot lobe phong --channel alpha" + out, "--channel");
  expect_usage_error("plot lobe phong --samples 2" + out, "--samples");
  expect_usage_error("plot lobe phong --size 800" + out, "--size: expected WIDTHxHEIGHT");
  expect_usage_error("plot lobe phong --size 10x600" + out, "--size: 10 x 600 is outside [64, 8192]");
  expect_usage_error("plot lobe phong --size 800x-6" + out, "--size");
  expect_usage_error("plot lobe phong --out " + dir + "lobe.jpg", "unknown extension '.jpg'");
  expect_usage_error("plot lobe phong --out " + dir + "no/such/dir/lobe.svg", "no/such/dir/lobe.svg");
  expect_usage_error("plot lobe phong --csv " + dir + "no/such/dir/lobe.csv" + out, "lobe.csv");
  expect_usage_error("plot lobe" + out, "MODEL");
  expect_usage_error("plot albedo phong --theta 90" + out, "--theta: 90 is out of range");
  expect_usage_error("plot fv --f0 1.5" + out, "--f0: 1.5 is out of range [0, 1]");
  expect_usage_error("plot fv --f0 0" + out, "log axis");
  expect_usage_error("plot fv --max-angle 90" + out, "--max-angle");
  expect_usage_error("plot zoo --n-min 0" + out, "--n-min");
  expect_usage_error("plot zoo --n-max 0.01" + out, "--n-max");
  expect_usage_error("plot zoo --row nosuchrow" + out, "unknown model 'nosuchrow'");
  expect_usage_error("plot zoo --relative --row phong" + out, "--relative");
  expect_usage_error("plot", "subcommand is required");
  const std::string sheet_out = " --out " + dir + "bad.png --cell 16 --spp 1";
  expect_usage_error("sheet lambert --vary n=10,100" + sheet_out, "unknown parameter 'n'");
  expect_usage_error("sheet phong --vary n" + sheet_out, "--vary");
  expect_usage_error("sheet phong --vary n=a,b" + sheet_out, "--vary");
  expect_usage_error("sheet phong --param n=3 --vary n=10" + sheet_out, "also given with --param");
  expect_usage_error("sheet phong --cell 512 --out " + dir + "bad.png", "--cell: 512 is out of range [16, 256]");
  expect_usage_error("sheet phong --light laser" + sheet_out, "--light");
  expect_usage_error("sheet phong --light-dir 0,0,0" + sheet_out, "--light-dir");
  expect_usage_error("sheet phong --hdri " + dir + "missing.exr" + sheet_out, "missing.exr");
  expect_usage_error("sheet phong --out " + dir + "sheet.svg", "--out: expected a .png file");
  expect_usage_error("sheet phong --spp 0" + sheet_out, "--spp");
  // A map that is not 2:1 is rejected before rendering.
  shadelab::Image square(8, 8);
  ASSERT_TRUE(shadelab::write_image(square, dir + "square.exr").has_value());
  expect_usage_error("sheet phong --hdri " + dir + "square.exr" + sheet_out, "twice as wide");
}


// Issue 10: plot lobe, plot albedo and sheet take the GGX family (ggx, burley, filament).
TEST(CliPlot, TheGgxFamilyInLobeAlbedoAndSheet) {
  const std::string dir = temp_dir();
  const auto lobe = json_of(run("plot lobe ggx burley filament --param ggx:roughness=0.4 --theta-in 30 --samples 37 "
                                "--out " + dir + "family_lobe.svg --json"));
  expect_svg(dir + "family_lobe.svg", 800, 600);
  ASSERT_EQ(lobe["series"].size(), 3u);
  std::vector<shadelab::BrdfPtr> models;
  models.push_back(brdf("ggx", {{"roughness", "0.4"}}));
  models.push_back(brdf("burley", {}));
  models.push_back(brdf("filament", {}));
  for (std::size_t m = 0; m < 3; ++m) {
    const auto& s = lobe["series"][m];
    for (std::size_t i = 3; i < 36; i += 8) {
      const double a = s["angle_deg"][i].get<double>();
      expect_rel(s["rgb"][i][1].get<double>(), models[m]->eval(plane_dir(-30.0), plane_dir(a)).g, 1e-12,
                 s["label"].get<std::string>() + " at " + std::to_string(a));
    }
  }
  // Albedo oracles: the white furnace (ggx with F = 1, kd = 0 and Kulla-Conty reflects 1, issue 10 section 2)
  // and Burley at roughness 0 seen from the normal: F_D90 = 1/2, albedo kd (1 - 2 int_0^1 (1-mu)^5 mu dmu / 2)
  // = kd (1 - B(2, 6)) = kd (1 - 1/42).
  const auto albedo = json_of(run("plot albedo ggx burley --param ggx:f=none --param ggx:kd=0 --param ggx:ms=kulla-conty "
                                  "--param ggx:roughness=0.8 --param burley:kd=1 --param burley:roughness=0 --theta 0 "
                                  "--theta 60 --out " + dir + "family_albedo.png --json"));
  expect_png(dir + "family_albedo.png", 800, 600);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_NEAR(albedo["series"][0]["rgb"][i][0].get<double>(), 1.0, 1e-3) << i;
  EXPECT_NEAR(albedo["series"][1]["rgb"][0][0].get<double>(), 1.0 - 1.0 / 42.0, 1e-6);

  const auto sheet = json_of(run("sheet ggx burley filament --cell 16 --spp 2 --light directional --out " + dir +
                                 "family_sheet.png --json"));
  expect_png(dir + "family_sheet.png", sheet["width"].get<int>(), sheet["height"].get<int>());
  ASSERT_EQ(sheet["cells"].size(), 3u);
  EXPECT_EQ(sheet["cells"][2]["model"], "filament");
}

}  // namespace
