// `shadelab explore`: the site it writes (the page, its script and the WebAssembly module, byte for byte
// the embedded files), its flag errors, and --serve answering HTTP on 127.0.0.1 with the same files. The
// page itself is tested in a browser by tools/explore/test/explorer.test.mjs.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>

#include <chrono>
#include <thread>

#include "cli_run.h"

namespace shadelab::testing {
namespace {

std::string read_all(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(CliExplore, WritesTheSite) {
  const auto dir = process_temp_dir("explore_site") / "nested" / "site";
  const CliRun r = run("explore --out " + dir.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("file://"), std::string::npos) << r.out;
  for (const char* name : {"index.html", "explorer.js", "explorer.css", "shadelab_wasm.js"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / name)) << name;
  }
  const std::string html = read_all(dir / "index.html");
  EXPECT_NE(html.find("id=\"shadelab-state\""), std::string::npos);
  EXPECT_NE(html.find("src=\"shadelab_wasm.js\""), std::string::npos);
  // The module is single-file (the wasm inlined), so it loads from file:// with no fetch.
  const std::string wasm = read_all(dir / "shadelab_wasm.js");
  EXPECT_GT(wasm.size(), 100000u);
  EXPECT_NE(wasm.find("createShadelab"), std::string::npos);
  EXPECT_NE(wasm.find("data:application/octet-stream;base64,"), std::string::npos);
}

// The HDRIs: every blender-data map baked into env-NAME.js, listed in environments.js with the default; the
// folder missing (no blender-data) is no error: the list says why there are none.
TEST(CliExplore, BakesTheHdris) {
  const std::filesystem::path world = "/usr/share/blender/datafiles/studiolights/world";
  if (!std::filesystem::is_directory(world)) GTEST_FAIL() << world << " is missing (scripts/setup.sh installs blender-data)";
  const auto dir = process_temp_dir("explore_hdri") / "site";
  const CliRun r = run("explore --out " + dir.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("baked 8 HDRIs"), std::string::npos) << r.out;
  for (const char* name : {"city", "courtyard", "forest", "interior", "night", "studio", "sunrise", "sunset"}) {
    const std::string js = read_all(dir / (std::string("env-") + name + ".js"));
    EXPECT_NE(js.find(std::string("[\"") + name + "\"] = {"), std::string::npos) << name;
    EXPECT_NE(js.find("\"texels\":\""), std::string::npos) << name;
    EXPECT_NE(js.find("\"file\":\"" + (world / (std::string(name) + ".exr")).string() + "\""), std::string::npos) << name;
    // 32^2 faces: the radiance cube and 6 prefiltered levels (32 .. 1), 6 x (32 + 63) rows of 32 RGB float32.
    EXPECT_NE(js.find("\"height\":570"), std::string::npos) << name;
  }
  const std::string index = read_all(dir / "environments.js");
  EXPECT_NE(index.find("\"default\":\"forest\""), std::string::npos) << index;
  EXPECT_NE(index.find("\"message\":null"), std::string::npos) << index;
}

TEST(CliExplore, NoHdriFolderIsNoError) {
  const auto dir = process_temp_dir("explore_no_hdri") / "site";
  const auto missing = process_temp_dir("explore_no_hdri") / "no-such-folder";
  const CliRun r = run("explore --out " + dir.string() + " --env-dir " + missing.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("no HDRI"), std::string::npos) << r.err;
  const std::string index = read_all(dir / "environments.js");
  EXPECT_NE(index.find("\"names\":[]"), std::string::npos) << index;
  EXPECT_NE(index.find("blender-data"), std::string::npos) << index;
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "index.html"));
  // A map that cannot be read is skipped and named.
  const auto bad = process_temp_dir("explore_bad_hdri");
  std::ofstream(bad / "broken.exr") << "not an exr";
  const CliRun b = run("explore --out " + (bad / "site").string() + " --env-dir " + bad.string());
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_NE(b.err.find("HDRI skipped: broken"), std::string::npos) << b.err;
  EXPECT_NE(read_all(bad / "site" / "environments.js").find("broken"), std::string::npos);
  const CliRun size = run("explore --out " + (bad / "site2").string() + " --env-size 24");
  EXPECT_EQ(size.code, 2);
  EXPECT_NE(size.err.find("--env-size"), std::string::npos) << size.err;
}

// The renderer's bake sizes, which the explorer's sphere test renders with.
TEST(CliExplore, RenderBakeSizeFlags) {
  const auto dir = process_temp_dir("explore_render");
  const auto scene = dir / "s.json";  // a small scene: the built-in one loads slowly
  std::ofstream(scene) << R"({"materials": {"m": {"model": "lambert"}},
                             "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})";
  const CliRun a = run("render " + scene.string() + " --env-size 32 --out " + (dir / "a.exr").string());
  EXPECT_EQ(a.code, 2);
  EXPECT_NE(a.err.find("--env-size"), std::string::npos) << a.err;
  const CliRun b = run("render " + scene.string() + " --mode game --specular-size 48 --out " + (dir / "b.exr").string());
  EXPECT_EQ(b.code, 2);
  EXPECT_NE(b.err.find("--specular-size"), std::string::npos) << b.err;
  const CliRun c = run("render " + scene.string() + " --mode game --env-size 0 --out " + (dir / "c.exr").string());
  EXPECT_EQ(c.code, 2);
  EXPECT_NE(c.err.find("--env-size"), std::string::npos) << c.err;
}

TEST(CliExplore, FlagErrors) {
  const CliRun r = run("explore --out " + (process_temp_dir("explore_flags") / "s").string() + " --port 9000");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--port"), std::string::npos) << r.err;
  const CliRun bad = run("explore --serve --port 70000 --out " + (process_temp_dir("explore_flags2") / "s").string());
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--port"), std::string::npos) << bad.err;
  // A file where the folder should be: one line naming it, exit 2.
  const auto file = process_temp_dir("explore_flags3") / "f";
  std::ofstream(file) << "x";
  const CliRun blocked = run("explore --out " + file.string());
  EXPECT_EQ(blocked.code, 2);
  EXPECT_NE(blocked.err.find(file.string()), std::string::npos) << blocked.err;
}

std::string http_get(int port, const std::string& target) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return {};
  }
  const std::string req = "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n";
  ::send(fd, req.data(), req.size(), 0);
  std::string out;
  char buf[65536];
  for (ssize_t n; (n = ::recv(fd, buf, sizeof buf, 0)) > 0;) out.append(buf, static_cast<std::size_t>(n));
  ::close(fd);
  return out;
}

TEST(CliExplore, ServesTheSiteOnLoopback) {
  const auto dir = process_temp_dir("explore_serve") / "site";
  const std::string out_file = (dir.parent_path() / "out.txt").string();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string out = "--out=" + dir.string();
    ::freopen(out_file.c_str(), "w", stdout);
    ::execl(SHADELAB_EXE, SHADELAB_EXE, "explore", "--serve", "--port", "0", out.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int port = 0;
  for (int i = 0; i < 200 && port == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const std::string text = read_all(out_file);
    const auto at = text.find("http://127.0.0.1:");
    if (at != std::string::npos && text.find('/', at + 17) != std::string::npos) port = std::stoi(text.substr(at + 17));
  }
  ASSERT_GT(port, 0) << read_all(out_file);
  const std::string index = http_get(port, "/");
  EXPECT_EQ(index.rfind("HTTP/1.1 200 OK\r\n", 0), 0u) << index.substr(0, 200);
  EXPECT_NE(index.find("Content-Type: text/html"), std::string::npos);
  EXPECT_NE(index.find(read_all(dir / "index.html")), std::string::npos);
  const std::string js = http_get(port, "/explorer.js?x=1");
  EXPECT_NE(js.find("Content-Type: text/javascript"), std::string::npos);
  EXPECT_EQ(http_get(port, "/../etc/passwd").rfind("HTTP/1.1 404", 0), 0u);
  EXPECT_EQ(http_get(port, "/missing.html").rfind("HTTP/1.1 404", 0), 0u);
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
}

}  // namespace
}  // namespace shadelab::testing
