// The registry's route to the measured model (issue 41, section 1): `measured` with `file=PATH` is built by
// load_measured_brdf from a MERL file the virtual gonioreflectometer wrote, equals the measured model at the bin
// centres, is loaded once per unchanged file, and refuses a missing, malformed or absent file in one line naming
// it. The class itself (interpolation, samplers) is tested by measured_test.cpp and analysis/measured_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "shadelab/brdf/measured.h"
#include "shadelab/brdf/merl.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/brdf/test_measured_file.h"
#include "shadelab/brdf/utia.h"

#include <fstream>

namespace shadelab {
namespace {

namespace fs = std::filesystem;

ParamAssignments file_param(const fs::path& p) { return {{"file", p.string()}}; }

TEST(MeasuredRegistry, IsRegisteredWithARequiredFileParameterAndNoShader) {
  const ModelInfo* m = find_brdf_model("measured");
  ASSERT_NE(m, nullptr);
  ASSERT_EQ(m->params.size(), 1u);
  EXPECT_EQ(m->params[0].name, "file");
  EXPECT_EQ(m->params[0].kind, ParamKind::file);
  EXPECT_STREQ(param_kind_name(ParamKind::file), "file");
  EXPECT_TRUE(is_required(m->params[0]));
  EXPECT_TRUE(needs_input_file(*m));
  EXPECT_FALSE(m->no_shader.empty());
  const auto others = std::count_if(brdf_models().begin(), brdf_models().end(), [](const ModelInfo& i) { return needs_input_file(i); });
  EXPECT_EQ(others, 1);  // only measured: every other model builds from its defaults
  // Its defaults parse (shadelab.models() and `brdf list` read them), the path empty.
  const auto defaults = parse_params(m->name, m->params, {});
  ASSERT_TRUE(defaults.has_value()) << defaults.error().message;
  EXPECT_EQ(defaults->file("file"), "");
}

TEST(MeasuredRegistry, EvalEqualsTheMeasuredModelAtBinCentres) {
  const auto made = make_brdf("measured", file_param(testing::measured_test_file()));
  ASSERT_TRUE(made.has_value()) << made.error().message;
  const auto source = make_brdf(testing::measured_source_model(), testing::measured_source_params());
  ASSERT_TRUE(source.has_value());
  double worst = 0.0;
  int compared = 0;
  for (int i : {0, 7, 30, 61, 88}) {
    for (int j : {0, 25, 50, 80}) {
      for (int k : {0, 45, 90, 179}) {
        const auto [a, b] = half_diff_directions(merl_bin_centre(i, j, k));
        const Vec3 wi = normalize(a), wo = normalize(b);
        if (!(wi.z > 1e-3 && wo.z > 1e-3)) continue;
        const Rgb want = (*source)->eval(wi, wo);
        const Rgb got = (*made)->eval(wi, wo);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(got[c] - want[c]) / want[c]);
        ++compared;
      }
    }
  }
  EXPECT_GE(compared, 40);
  // At a centre the interpolation weights are 1 and 0 up to the rounding of the angles: the file's value, which is
  // f / scale * scale.
  EXPECT_LE(worst, 1e-9);
  // Off the centres it is an interpolation of the model, not the model: a pair between centres differs.
  const Vec3 wi = normalize(Vec3{0.31, 0.05, 0.9}), wo = normalize(Vec3{-0.33, 0.0, 0.9});
  EXPECT_NE((*made)->eval(wi, wo).g, (*source)->eval(wi, wo).g);
}

TEST(MeasuredRegistry, AnUnchangedFileIsReadOnceAndAChangedOneAgain) {
  const fs::path& path = testing::measured_test_file();
  ASSERT_TRUE(make_brdf("measured", file_param(path)).has_value());
  const std::size_t reads = measured_file_reads();
  std::vector<BrdfPtr> many;  // a scene of many spheres of the same file
  for (int i = 0; i < 20; ++i) many.push_back(std::move(make_brdf("measured", file_param(path)).value()));
  // Another spelling of the same file: the cache key is the canonical path.
  many.push_back(std::move(make_brdf("measured", file_param(path.parent_path() / "." / path.filename())).value()));
  EXPECT_EQ(measured_file_reads(), reads);
  const Vec3 wi = normalize(Vec3{0.2, 0.1, 0.9}), wo = normalize(Vec3{-0.4, 0.0, 0.8});
  EXPECT_EQ(many.front()->eval(wi, wo).g, many.back()->eval(wi, wo).g);
  EXPECT_EQ(many.front()->pdf(wi, wo), many.back()->pdf(wi, wo));
  // A new modification time is a new file: read again.
  const auto t = fs::last_write_time(path);
  fs::last_write_time(path, t + std::chrono::seconds(2));
  ASSERT_TRUE(make_brdf("measured", file_param(path)).has_value());
  EXPECT_EQ(measured_file_reads(), reads + 1);
  fs::last_write_time(path, t);
}

// The error of make_brdf("measured", params): one line.
std::string error_of(const ParamAssignments& params) {
  const auto r = make_brdf("measured", params);
  if (r) return "(no error)";
  EXPECT_EQ(r.error().message.find('\n'), std::string::npos) << r.error().message;
  return r.error().message;
}

TEST(MeasuredRegistry, BadFilesAndParametersAreOneLineNamingTheFile) {
  const fs::path dir = testing::measured_test_folder().dir();
  ASSERT_FALSE(dir.empty());
  EXPECT_EQ(error_of({}), "brdf measured: parameter 'file' is required (a MERL 100 .binary (34,992,012 bytes), RGL .bsdf "
                          "(RGB) or UTIA .bin file; in a scene, relative to the scene file's folder)");
  EXPECT_EQ(error_of({{"file", ""}}), "brdf measured: parameter 'file' is an empty path");
  EXPECT_EQ(error_of({{"files", "x.binary"}}), "brdf measured: unknown parameter 'files' (parameters: file)");
  const fs::path missing = dir / "missing.binary";
  EXPECT_EQ(error_of(file_param(missing)).rfind("brdf measured: parameter 'file': " + missing.string() + ": cannot read (", 0), 0u)
      << error_of(file_param(missing));
  std::vector<char> head(100, '\0');
  const std::int32_t dims[3] = {90, 90, 180};
  std::memcpy(head.data(), dims, sizeof dims);
  const fs::path small = testing::write_test_file("small.binary", head);
  EXPECT_EQ(error_of(file_param(small)), "brdf measured: parameter 'file': " + small.string() +
                                             ": 100 bytes, expected 34992012 (a 12-byte header and three planes of 90 x "
                                             "90 x 180 float64): truncated");
  const fs::path zeros = testing::write_test_file("zeros.binary", std::vector<char>(100, '\0'));
  EXPECT_EQ(error_of(file_param(zeros)), "brdf measured: parameter 'file': " + zeros.string() +
                                             ": header dims 0 x 0 x 0, expected MERL's 90 x 90 x 180 (theta_h, theta_d, phi_d)");
  EXPECT_EQ(error_of(file_param(dir)), "brdf measured: parameter 'file': " + dir.string() + ": not a regular file");
}

}  // namespace
}  // namespace shadelab

namespace shadelab {
namespace {

TEST(MeasuredRegistry, UtiaAndRglFilesAreReadByTheirReaders) {
  // The extension chooses the reader: a UTIA file of ward through the registry equals read_utia_brdf's BRDF.
  auto ward = make_brdf("ward", {{"kd", "0.3"}, {"ks", "0.2"}, {"alpha", "0.4"}});
  ASSERT_TRUE(ward);
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "shadelab_registry_ward.bin";
  const std::vector<char> bytes = encode_utia(measure_utia(**ward));
  {
    std::ofstream out(file, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  auto via_registry = make_brdf("measured", {{"file", file.string()}});
  ASSERT_TRUE(via_registry) << via_registry.error().message;
  auto direct = read_utia_brdf(file);
  ASSERT_TRUE(direct);
  EXPECT_TRUE((*via_registry)->is_tabulated());
  for (const auto& [wi, wo] : {std::pair{Vec3{0.3, 0.1, 0.9}, Vec3{-0.4, 0.2, 0.8}}, std::pair{Vec3{0.0, 0.6, 0.8}, Vec3{0.5, -0.5, 0.7}}}) {
    const Rgb a = (*via_registry)->eval(normalize(wi), normalize(wo));
    const Rgb b = (*direct)->eval(normalize(wi), normalize(wo));
    EXPECT_EQ(a.r, b.r);
    EXPECT_GT(a.r, 0.0);
  }
  // A .bsdf that is not a tensor file is refused by the RGL reader, naming the file.
  const std::filesystem::path bad = std::filesystem::temp_directory_path() / "shadelab_registry_bad.bsdf";
  {
    std::ofstream out(bad, std::ios::binary);
    out << "not a tensor file";
  }
  const auto refused = make_brdf("measured", {{"file", bad.string()}});
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("shadelab_registry_bad.bsdf"), std::string::npos) << refused.error().message;
  std::filesystem::remove(file);
  std::filesystem::remove(bad);
}

}  // namespace
}  // namespace shadelab
