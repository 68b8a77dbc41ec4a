// The exporter's view of the kernel text: files in kernels.h's (dependency) order, each model's closure of
// kernel files, the parameter structs, and the errors a malformed kernel set gives.
#include "kernel_library.h"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

namespace shadelab::shaders {
namespace {

std::vector<std::string> names_of(const KernelLibrary& lib, const std::vector<std::size_t>& files) {
  std::vector<std::string> out;
  for (std::size_t f : files) out.push_back(lib.files()[f].name);
  return out;
}

TEST(KernelLibrary, EmbeddedFilesAreKernelsHInOrder) {
  std::ifstream in(SHADELAB_KERNELS_H);
  ASSERT_TRUE(in) << SHADELAB_KERNELS_H;
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  const std::regex include(R"re(#include "shadelab/kernels/([a-z0-9_]+\.sl)")re");
  std::vector<std::string> expected;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), include); it != std::sregex_iterator(); ++it) {
    expected.push_back((*it)[1]);
  }
  std::vector<std::string> embedded;
  for (const auto& f : embedded_kernel_files()) embedded.push_back(f.name);
  EXPECT_EQ(embedded, expected);
  EXPECT_GE(embedded.size(), 13u);
}

TEST(KernelLibrary, ClosureIsWhatAModelNeedsInDependencyOrder) {
  const KernelLibrary& lib = KernelLibrary::embedded();
  EXPECT_EQ(names_of(lib, lib.closure({"lambert_prepare", "lambert_eval"})),
            (std::vector<std::string>{"common.sl", "lambert.sl"}));
  EXPECT_EQ(names_of(lib, lib.closure({"cook_torrance_eval"})),
            (std::vector<std::string>{"erf.sl", "common.sl", "fresnel.sl", "microfacet.sl", "cook_torrance.sl"}));
  EXPECT_EQ(names_of(lib, lib.closure({"minimalist_cook_torrance_eval"})),
            (std::vector<std::string>{"erf.sl", "common.sl", "microfacet.sl", "minimalist_cook_torrance.sl"}));  // whole files: microfacet.sl's Smith term uses erf
  EXPECT_EQ(names_of(lib, lib.closure({"sh9_irradiance_game"})), (std::vector<std::string>{"common.sl", "sh9.sl"}));
  EXPECT_TRUE(lib.closure({"no_such_function"}).empty());
}

TEST(KernelLibrary, ParameterStructs) {
  const KernelLibrary& lib = KernelLibrary::embedded();
  ASSERT_EQ(lib.prepare_parameter_type("phong"), std::optional<std::string>("PhongParams"));
  const StructDecl* p = lib.find_struct("PhongParams");
  ASSERT_NE(p, nullptr);
  ASSERT_EQ(p->fields.size(), 5u);
  EXPECT_EQ(p->fields[0].name, "kd");
  EXPECT_EQ(p->fields[0].type, FieldType::rgb);
  EXPECT_EQ(p->fields[2].name, "n");
  EXPECT_EQ(p->fields[2].type, FieldType::real);
  EXPECT_EQ(p->fields[3].type, FieldType::integer);
  const StructDecl* l = lib.find_struct("LafortuneParams");
  ASSERT_NE(l, nullptr);
  EXPECT_EQ(l->fields[3].name, "cx");
  EXPECT_EQ(l->fields[3].array_size, 8);
  EXPECT_EQ(l->fields[3].scalar_count(), 8);
  EXPECT_EQ(lib.int_constant("LAFORTUNE_MAX_LOBES"), std::optional<long long>(8));
  // Every kernel with a prepare function has its parameter struct.
  for (const std::string k : {"lambert", "phong", "blinn_phong", "cook_torrance", "minimalist_cook_torrance", "ward",
                              "lafortune", "wrapped_diffuse"}) {
    const auto t = lib.prepare_parameter_type(k);
    ASSERT_TRUE(t.has_value()) << k;
    EXPECT_NE(lib.find_struct(*t), nullptr) << k;
  }
}

TEST(KernelLibrary, ErrorsNameTheFileAndName) {
  auto later = KernelLibrary::parse({{"a.sl", "inline real f(real x) { return g(x); }\n"},
                                     {"b.sl", "inline real g(real x) { return x; }\n"}});
  ASSERT_FALSE(later.has_value());
  EXPECT_EQ(later.error().message,
            "kernel a.sl uses 'g', defined in the later file b.sl (list the files in dependency order)");
  auto twice = KernelLibrary::parse({{"a.sl", "const real X = 1.0;\n"}, {"b.sl", "\n\nconst real X = 2.0;\n"}});
  ASSERT_FALSE(twice.has_value());
  EXPECT_EQ(twice.error().message, "kernel b.sl:3: 'X' is defined twice");
  auto size = KernelLibrary::parse({{"a.sl", "struct P {\n  real c[M];\n};\n"}});
  ASSERT_FALSE(size.has_value());
  EXPECT_EQ(size.error().message, "kernel a.sl:2: array size 'M' is not an int constant defined before it");
  auto ok = KernelLibrary::parse({{"a.sl", "const int M = 4;\n"}, {"b.sl", "struct P { real c[M]; rgb k; };\n"}});
  ASSERT_TRUE(ok.has_value()) << ok.error().message;
  EXPECT_EQ(ok->find_struct("P")->fields[0].array_size, 4);
  EXPECT_EQ(ok->find_struct("P")->fields[1].scalar_count(), 3);
  // A GLSL keyword as a variable (what game_ibl.sl once had: `DfgScaleBias out;`) is refused with its line.
  auto reserved = KernelLibrary::parse({{"a.sl", "inline real f(real x) {\n  real out = x;\n  return out;\n}\n"}});
  ASSERT_FALSE(reserved.has_value());
  EXPECT_EQ(reserved.error().message, "kernel a.sl:2: 'out' is a reserved word in GLSL or HLSL: name it otherwise");
}

}  // namespace
}  // namespace shadelab::shaders
