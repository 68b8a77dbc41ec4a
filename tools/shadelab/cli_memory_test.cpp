// Memory bounds proved under RLIMIT_AS (issue 16, section 6; docs/testing.md, "Memory bounds"). Each test
// forks a child, lets it warm up (libraries, thread pools), reads how much address space it uses, limits
// its growth with setrlimit(RLIMIT_AS) to the stated budget plus a small allowance for bookkeeping, and then
// does the work: if the work needed more than the budget, an allocation would fail and the child would
// report it. Address space over-counts memory (thread stacks and malloc arenas are reserved, not used), so
// a pass is conservative.
//
// AddressSanitizer reserves terabytes of address space for its shadow memory, so RLIMIT_AS cannot be used
// under it: in the sanitize build these tests are skipped (the ordinary build runs them).
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "shadelab/image/image_io.h"
#include "shadelab/render/film.h"
#include "shadelab/render/game_renderer.h"
#include "shadelab/render/path_tracer.h"
#include "shadelab/scene/limits.h"
#include "shadelab/scene/scene_json.h"

#if defined(__SANITIZE_ADDRESS__)
#define SHADELAB_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SHADELAB_UNDER_ASAN 1
#endif
#endif

namespace {

namespace fs = std::filesystem;
using namespace shadelab;

#ifdef SHADELAB_UNDER_ASAN
#define SKIP_UNDER_ASAN() GTEST_SKIP() << "RLIMIT_AS cannot be used under AddressSanitizer; the ordinary build runs this test"
#else
#define SKIP_UNDER_ASAN() (void)0
#endif

constexpr std::uint64_t MiB = 1ULL << 20;
// What the allocator and the libraries may add beyond the budget: malloc's headers and arena growth,
// OpenEXR's and Embree's small tables, a TBB task or two.
constexpr std::uint64_t bookkeeping = 32 * MiB;

const fs::path& dir() {
  static const fs::path d = shadelab::testing::process_temp_dir("shadelab_memory");
  return d;
}

// The address space this process uses now: /proc/self/statm's first field, in pages.
std::uint64_t address_space_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  statm >> pages;
  return pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

// Runs warm_up, then limits the address space to what is used plus `extra` bytes and runs body, in a forked
// child. Returns the child's exit code (body's return value), or 128 + the signal that ended it.
int run_limited(const std::function<void()>& warm_up, std::uint64_t extra, const std::function<int()>& body) {
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    warm_up();
    const rlimit limit{address_space_bytes() + extra, RLIM_INFINITY};
    if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(100);
    const int code = body();
    std::fflush(nullptr);
    ::_exit(code);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void write_bytes(const fs::path& p, const std::vector<char>& bytes) {
  std::ofstream f(p, std::ios::binary);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// A 1 x 1 uncompressed EXR of grey 0.5, the small valid file the bombs below patch.
void write_one_pixel_exr(const fs::path& p) {
  Image one(1, 1);
  one.set(0, 0, Rgb::gray(0.5));
  WriteOptions o;
  o.exr_compression = ExrCompression::none;
  EXPECT_TRUE(write_image(one, p, o));
}

// An EXR of one pixel whose display window is width x height: the reader allocates the whole display
// window (black outside the data window) from a file of a few hundred bytes. Written by write_image, then
// the displayWindow attribute (box2i: xmin, ymin, xmax, ymax) patched.
fs::path bomb_exr(const std::string& name, int width, int height) {
  const fs::path p = dir() / name;
  write_one_pixel_exr(p);
  std::string text = read_text(p);
  std::vector<char> bytes(text.begin(), text.end());
  const std::string key("displayWindow\0box2i\0", 20);
  const auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
  EXPECT_NE(at, bytes.end());
  const std::int32_t box[4] = {0, 0, width - 1, height - 1};
  std::memcpy(&*(at + static_cast<long>(key.size()) + 4), box, sizeof box);
  write_bytes(p, bytes);
  return p;
}

// The largest square display window within the image read budget (12 bytes a pixel): 9459 x 9459, 1024 MiB;
// with aspect 2, the largest lat-long: 13376 x 6688.
int largest_within_the_read_budget(int aspect) {
  int side = 1;
  while (12ULL * static_cast<std::uint64_t>(aspect) * static_cast<std::uint64_t>(side + 1) *
             static_cast<std::uint64_t>(side + 1) <= image_read_budget_bytes) {
    ++side;
  }
  return side;
}
int largest_square_within_the_read_budget() { return largest_within_the_read_budget(1); }

void warm_up_image_reader() {
  Image small(4, 2);
  (void)write_image(small, dir() / "warm.exr");
  (void)read_image(dir() / "warm.exr");
}

// ---- image reads: image_read_budget_bytes ----------------------------------------------------------------

// A read at the budget (a 1024 MiB display window from a 400-byte file) succeeds within the budget: the
// reader allocates the image once, no second buffer of its size.
TEST(MemoryBound, ImageReadAtTheBudgetStaysWithinIt) {
  SKIP_UNDER_ASAN();
  const int side = largest_square_within_the_read_budget();
  const fs::path p = bomb_exr("at_budget.exr", side, side);
  ASSERT_LT(fs::file_size(p), 1000u);
  const int code = run_limited(warm_up_image_reader, image_read_budget_bytes + bookkeeping, [&] {
    const Result<Image> image = read_image(p);
    if (!image) {
      std::fprintf(stderr, "%s\n", image.error().message.c_str());
      return 1;
    }
    return image->width == side && image->height == side && image->at(0, 0).r == 0.5 ? 0 : 2;
  });
  EXPECT_EQ(code, 0);
}

// The same read with less memory than it needs is an error naming the file ("out of memory"), not an
// exception, a crash or exit code 3: read_image turns std::bad_alloc into an Error.
TEST(MemoryBound, ImageReadOutOfMemoryIsAnErrorNamingTheFile) {
  SKIP_UNDER_ASAN();
  const int side = largest_square_within_the_read_budget();
  const fs::path p = bomb_exr("oom.exr", side, side);
  const int code = run_limited(warm_up_image_reader, 256 * MiB, [&] {
    const Result<Image> image = read_image(p);
    if (image) return 1;
    const std::string& m = image.error().message;
    std::fprintf(stderr, "%s\n", m.c_str());
    return m.find(p.string()) != std::string::npos && m.find("out of memory") != std::string::npos ? 0 : 2;
  });
  EXPECT_EQ(code, 0);
}

// ---- scenes: max_scene_image_bytes ---------------------------------------------------------------------

// Images a scene names past its budget are refused from their headers (each read gets only what is left),
// so a scene's textures never take more than max_scene_image_bytes, however many it names; a procedural
// texture is charged before it is generated.
TEST(MemoryBound, SceneImagesStayWithinTheSceneBudget) {
  SKIP_UNDER_ASAN();
  const int side = largest_square_within_the_read_budget();  // 1024 MiB each: two fill the budget
  bomb_exr("t1.exr", side, side);
  bomb_exr("t2.exr", side, side);
  bomb_exr("t3.exr", 256, 256);  // 768 KiB: more than the 136 KiB the first two leave
  auto scene_with = [&](const std::string& third) {
    const fs::path p = dir() / ("scene_" + std::to_string(third.size()) + ".json");
    const std::string text = R"({"textures": {"a": {"file": "t1.exr"}, "b": {"file": "t2.exr"}, "c": )" + third + "}}";
    write_bytes(p, std::vector<char>(text.begin(), text.end()));
    return p;
  };
  const fs::path file_third = scene_with(R"({"file": "t3.exr"})");
  const fs::path procedural_third = scene_with(R"({"procedural": "checker", "size": 256})");
  const int code = run_limited(warm_up_image_reader, max_scene_image_bytes + bookkeeping, [&] {
    int wrong = 0;
    for (const auto& [p, pointer] : {std::pair{file_third, "/textures/c/file"}, std::pair{procedural_third, "/textures/c/size"}}) {
      const Result<Scene> scene = load_scene(p);
      const std::string m = scene ? std::string("loaded") : scene.error().message;
      std::fprintf(stderr, "%s\n", m.c_str());
      wrong += m.find(pointer) != std::string::npos && m.find("2048 MiB in all") != std::string::npos ? 0 : 1;
    }
    return wrong;
  });
  EXPECT_EQ(code, 0);
}

// ---- renders: render_bytes_per_pixel -------------------------------------------------------------------

Scene render_scene_of(int width, int height) {
  const std::string text = R"({"camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0], "width": )" +
                           std::to_string(width) + R"(, "height": )" + std::to_string(height) +
                           R"(}, "render": {"spp": 1, "max_depth": 2},
      "materials": {"m": {"model": "lambert"}},
      "shapes": [{"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "m"}],
      "lights": [{"type": "point", "position": [0, 3, 2], "intensity": 5}], "environment": {"uniform": 0.2}})";
  const fs::path p = dir() / ("render_" + std::to_string(width) + ".json");
  write_bytes(p, std::vector<char>(text.begin(), text.end()));
  auto scene = load_scene(p);
  EXPECT_TRUE(scene) << scene.error().message;
  return scene ? std::move(scene).value() : Scene{};
}

// Renders and writes the EXR and PNG (and the AOVs), as `shadelab render` does.
int render_and_write(const Scene& scene, bool aovs, bool game) {
  Result<RenderResult> result = make_error("");
  if (game) {
    GameOptions go;
    go.spp = 1;
    result = render_game(scene, go);
  } else {
    RenderOptions ro;
    ro.aovs = aovs;
    result = render_scene(scene, ro);
  }
  if (!result) {
    std::fprintf(stderr, "%s\n", result.error().message.c_str());
    return 1;
  }
  FilmOutputs film;
  film.exr = dir() / (game ? "game.exr" : "render.exr");
  film.png = dir() / (game ? "game.png" : "render.png");
  film.aovs = aovs;
  auto written = write_film(*result, film);
  if (!written) std::fprintf(stderr, "%s\n", written.error().message.c_str());
  return written ? 0 : 1;
}

// A 2048 x 2048 render with its files fits in render_bytes_per_pixel (render_aov_bytes_per_pixel with
// AOVs) per pixel beyond what the same scene took at 8 x 8: at max_render_pixels that is the stated 3 GiB
// (7 GiB with AOVs). Both renderers.
TEST(MemoryBound, RenderStaysWithinItsPerPixelBudget) {
  SKIP_UNDER_ASAN();
  const int w = 2048;
  const int h = 2048;
  const auto pixels = static_cast<std::uint64_t>(w) * h;
  for (const auto& [aovs, game, per_pixel] : {std::tuple{false, false, render_bytes_per_pixel},
                                              std::tuple{true, false, render_aov_bytes_per_pixel},
                                              std::tuple{false, true, render_bytes_per_pixel}}) {
    const Scene small = render_scene_of(8, 8);
    const Scene big = render_scene_of(w, h);
    const int code = run_limited([&, aovs = aovs, game = game] { (void)render_and_write(small, aovs, game); },
                                 per_pixel * pixels + bookkeeping,
                                 [&, aovs = aovs, game = game] { return render_and_write(big, aovs, game); });
    EXPECT_EQ(code, 0) << "aovs " << aovs << ", game " << game << ": " << per_pixel << " bytes per pixel";
  }
  EXPECT_EQ(static_cast<std::uint64_t>(max_render_pixels) * render_bytes_per_pixel, 3ULL << 30);
}

// ---- the CLI's out-of-memory path ----------------------------------------------------------------------

// Runs the shadelab binary with its address space limited to `limit` bytes; returns the exit code and stderr.
shadelab::testing::CliRun run_cli_limited(std::uint64_t limit, const std::vector<std::string>& args) {
  const fs::path err = dir() / "err.txt";
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const rlimit l{limit, limit};
    ::setrlimit(RLIMIT_AS, &l);
    std::vector<const char*> argv{SHADELAB_EXE};
    for (const auto& a : args) argv.push_back(a.c_str());
    argv.push_back(nullptr);
    if (std::freopen(err.c_str(), "w", stderr) == nullptr || std::freopen("/dev/null", "w", stdout) == nullptr) ::_exit(101);
    ::execv(SHADELAB_EXE, const_cast<char* const*>(argv.data()));
    ::_exit(102);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  shadelab::testing::CliRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.err = read_text(err);
  return r;
}

// A render at the pixel cap (8192 x 4096: 1.2 GB of accumulators and image) in 1 GiB of address space, and
// a lat-long at the read budget (1024 MiB) baked there: std::bad_alloc becomes exit code 2 with one line saying "out of memory",
// never a crash or exit code 3.
TEST(MemoryBound, OutOfMemoryIsExitCodeTwoWithOneLine) {
  SKIP_UNDER_ASAN();
  const std::string cap = R"({"camera": {"width": 8192, "height": 4096}, "render": {"spp": 1, "max_depth": 1},
      "materials": {"m": {"model": "lambert"}},
      "shapes": [{"type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "m"}]})";
  write_bytes(dir() / "cap.json", std::vector<char>(cap.begin(), cap.end()));
  const int h = largest_within_the_read_budget(2);
  bomb_exr("latlong.exr", 2 * h, h);  // 2:1, 1024 MiB: within the read budget, not within 1 GiB of address space
  const std::string out = (dir() / "oom.exr").string();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"render", (dir() / "cap.json").string(), "--out", out, "--no-png"},
        std::vector<std::string>{"bake", "sh", (dir() / "latlong.exr").string()}}) {
    const auto r = run_cli_limited(1ULL << 30, args);
    EXPECT_EQ(r.code, 2) << args[0] << " " << args[1] << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("out of memory"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

// issue 40, finding 3: a small valid EXR (1 x 1, float, uncompressed) with a string attribute "comments"
// added to its header (the line offset moved by what was inserted), then that attribute's size patched to
// `claimed` bytes. OpenEXR allocates a string attribute's claimed size before reading it: 0x7fffffff took
// 2.1 GB before `compare` exited 2.
fs::path claiming_exr(const std::string& name, std::int32_t claimed) {
  const fs::path p = dir() / name;
  write_one_pixel_exr(p);
  std::string bytes = read_text(p);
  const std::string value = "hello";
  std::string attribute("comments\0string\0", 16);
  const auto size = static_cast<std::int32_t>(value.size());
  attribute.append(reinterpret_cast<const char*>(&size), 4).append(value);
  // The file ends with the one offset (uint64), then the scan line: y (int32), byte count (int32), B G R floats.
  const std::size_t offset_at = bytes.size() - 8 - 4 - 4 - 12;
  std::uint64_t offset = 0;
  std::memcpy(&offset, bytes.data() + offset_at, 8);
  EXPECT_EQ(offset, offset_at + 8) << "not the expected layout";
  offset += attribute.size();
  std::memcpy(bytes.data() + offset_at, &offset, 8);
  bytes = bytes.substr(0, 8) + attribute + bytes.substr(8);  // the first attribute, after magic and version
  std::memcpy(bytes.data() + 8 + 16, &claimed, 4);
  write_bytes(p, std::vector<char>(bytes.begin(), bytes.end()));
  return p;
}

// Header sizes are bounded by the file's size before OpenEXR allocates anything: with the attribute's true
// size the file reads (the construction is a valid EXR); claiming 0x7fffffff bytes (or a negative size, or
// one byte more than the file holds) it is one line naming the file and the attribute, exit 2, and the CLI
// (`compare`, and `merge` reading it as a part) does so in 256 MiB of address space: nothing in proportion to
// the claim was allocated. Before the check: `compare` needed 2.1 GB, and under this limit said "out of memory".
TEST(MemoryBound, ExrHeaderAttributeSizesAreBoundedByTheFile) {
  SKIP_UNDER_ASAN();
  const fs::path valid = claiming_exr("valid.exr", 5);
  const auto ok = read_image(valid);
  ASSERT_TRUE(ok) << ok.error().message;
  EXPECT_EQ(ok->at(0, 0).g, 0.5);
  const std::uint64_t file_bytes = fs::file_size(valid);
  for (const std::int32_t claimed : {std::int32_t{0x7fffffff}, std::int32_t{-1}, static_cast<std::int32_t>(file_bytes)}) {
    const fs::path bad = claiming_exr("claims.exr", claimed);
    const auto r = read_image(bad);
    ASSERT_FALSE(r) << claimed;
    EXPECT_NE(r.error().message.find("read_image: '" + bad.string() + "': header attribute 'comments' (type 'string') claims " +
                                     std::to_string(claimed) + " bytes, but the file has "),
              std::string::npos)
        << r.error().message;
  }
  const fs::path bad = claiming_exr("claims.exr", 0x7fffffff);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"compare", bad.string(), valid.string()},
        std::vector<std::string>{"merge", bad.string(), "--out", (dir() / "merged.exr").string()}}) {
    const auto r = run_cli_limited(256 * MiB, args);
    EXPECT_EQ(r.code, 2) << args[0] << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("'" + bad.string() + "'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("header attribute 'comments' (type 'string') claims 2147483647 bytes"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("out of memory"), std::string::npos) << r.err;
  }
}

// The pixel cap itself: one pixel more than max_render_pixels is refused from the scene, exit code 2.
TEST(MemoryBound, CameraBeyondThePixelCapIsRefused) {
  const std::string over = R"({"camera": {"width": 16384, "height": 2049}})";
  write_bytes(dir() / "over.json", std::vector<char>(over.begin(), over.end()));
  shadelab::testing::expect_usage_error("render " + (dir() / "over.json").string() + " --out " +
                                            (dir() / "over.exr").string(),
                                        "/camera/height: 16384 x 2049 is 33570816 pixels, more than the limit of 33554432");
  const std::string at = R"({"camera": {"width": 16384, "height": 2048}})";
  write_bytes(dir() / "at.json", std::vector<char>(at.begin(), at.end()));
  EXPECT_TRUE(load_scene(dir() / "at.json"));
}

}  // namespace
