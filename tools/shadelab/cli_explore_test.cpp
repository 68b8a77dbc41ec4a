// `shadelab explore`: the site it writes (the page, its script and the WebAssembly module, byte for byte
// the embedded files), its flag errors, and --serve answering HTTP on 127.0.0.1 with the same files. The
// page itself is tested in a browser by tools/explore/test/explorer.test.mjs.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>

#include <sys/time.h>

#include <chrono>
#include <thread>
#include <vector>

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
    // 32^2 faces: the radiance cube, 6 Phong-prefiltered levels (32 .. 1) and the 6 levels of the GGX chain,
    // 6 x (32 + 63 + 63) rows of 32 RGB float32; the split sum's tables beside them.
    EXPECT_NE(js.find("\"height\":948"), std::string::npos) << name;
    EXPECT_NE(js.find("\"ggx_first_block\":7,\"ggx_levels\":6,\"ggx_mapping\":\"linear\""), std::string::npos) << name;
    EXPECT_NE(js.find("\"dfg_size\":64"), std::string::npos) << name;
    EXPECT_NE(js.find("\"lobe_size\":32"), std::string::npos) << name;
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

// ---------------------------------------------------------------------------------------- explore --serve
// The served site against any local process as a client (issue 40): each test starts its own server
// (`explore --serve --port 0`, no HDRIs to bake) and kills it at the end; every client socket has a 3 s
// connect, send and receive timeout, so a server that stops answering fails the test instead of hanging it.

// Connects to addr:port; -1 when refused.
int connect_to(int port, const char* addr = "127.0.0.1") {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  ::inet_pton(AF_INET, addr, &a.sin_addr);
  const timeval timeout{3, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof timeout);  // bounds connect() too (a full backlog)
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

// Everything the server sends until it closes (or 3 s of silence).
std::string receive_all(int fd) {
  std::string out;
  char buf[65536];
  for (ssize_t n; (n = ::recv(fd, buf, sizeof buf, 0)) > 0;) out.append(buf, static_cast<std::size_t>(n));
  return out;
}

// Sends `request` as it is and returns the whole answer.
std::string send_request(int port, const std::string& request) {
  const int fd = connect_to(port);
  if (fd < 0) return "(refused)";
  ::send(fd, request.data(), request.size(), MSG_NOSIGNAL);
  std::string out = receive_all(fd);
  ::close(fd);
  return out;
}

std::string http_get(int port, const std::string& target, const std::string& method = "GET") {
  return send_request(port, method + " " + target + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) + "\r\n\r\n");
}

std::string status_line(const std::string& response) { return response.substr(0, response.find("\r\n")); }

class CliServe : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = process_temp_dir("explore_serve") / "site";
    const std::string out_file = (m_dir.parent_path() / "out.txt").string();
    const std::string env_dir = (m_dir.parent_path() / "no-hdris").string();
    m_pid = ::fork();
    ASSERT_GE(m_pid, 0);
    if (m_pid == 0) {
      const std::string out = "--out=" + m_dir.string();
      const std::string env = "--env-dir=" + env_dir;
      if (::freopen(out_file.c_str(), "w", stdout) == nullptr) ::_exit(126);
      ::execl(SHADELAB_EXE, SHADELAB_EXE, "explore", "--serve", "--port", "0", out.c_str(), env.c_str(),
              static_cast<char*>(nullptr));
      ::_exit(127);
    }
    for (int i = 0; i < 300 && m_port == 0; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      const std::string text = read_all(out_file);
      const auto at = text.find("http://127.0.0.1:");
      if (at != std::string::npos && text.find('/', at + 17) != std::string::npos) m_port = std::stoi(text.substr(at + 17));
    }
    ASSERT_GT(m_port, 0) << read_all(out_file);
  }
  void TearDown() override {
    if (m_pid > 0) {
      ::kill(m_pid, SIGKILL);
      ::waitpid(m_pid, nullptr, 0);
    }
  }
  // The server process has not exited.
  bool alive() const { return ::waitpid(m_pid, nullptr, WNOHANG) == 0; }

  std::filesystem::path m_dir;
  pid_t m_pid = -1;
  int m_port = 0;
};

TEST_F(CliServe, ServesTheSiteOnLoopback) {
  const std::string index = http_get(m_port, "/");
  EXPECT_EQ(index.rfind("HTTP/1.1 200 OK\r\n", 0), 0u) << index.substr(0, 200);
  EXPECT_NE(index.find("Content-Type: text/html"), std::string::npos);
  EXPECT_NE(index.find(read_all(m_dir / "index.html")), std::string::npos);
  const std::string js = http_get(m_port, "/explorer.js?x=1");
  EXPECT_NE(js.find("Content-Type: text/javascript"), std::string::npos);
  const std::string wasm = http_get(m_port, "/shadelab_wasm.js");  // streamed, megabytes
  EXPECT_EQ(wasm.size() - wasm.find("\r\n\r\n") - 4, std::filesystem::file_size(m_dir / "shadelab_wasm.js"));
  EXPECT_EQ(status_line(http_get(m_port, "/missing.html")), "HTTP/1.1 404 Not Found");
  // The Host of a page from another name (DNS rebinding) or none with HTTP/1.1: 400; localhost is this server.
  EXPECT_EQ(status_line(send_request(m_port, "GET / HTTP/1.1\r\nHost: evil.example\r\n\r\n")), "HTTP/1.1 400 Bad Request");
  EXPECT_EQ(status_line(send_request(m_port, "GET / HTTP/1.1\r\nHost: 127.0.0.1:1\r\n\r\n")), "HTTP/1.1 400 Bad Request");
  EXPECT_EQ(status_line(send_request(m_port, "GET / HTTP/1.1\r\n\r\n")), "HTTP/1.1 400 Bad Request");
  EXPECT_EQ(status_line(send_request(m_port, "GET / HTTP/1.1\r\nHost: localhost:" + std::to_string(m_port) + "\r\n\r\n")),
            "HTTP/1.1 200 OK");
  EXPECT_EQ(status_line(send_request(m_port, "GET / HTTP/1.0\r\n\r\n")), "HTTP/1.1 200 OK");
}

// Before issue 40 each of these ended the server with exit 3 ("internal error: basic_string::substr").
TEST_F(CliServe, MalformedRequestsGet400AndTheServerGoesOn) {
  for (const std::string request : {"GET ?x HTTP/1.1\r\n\r\n", "GET\r\n\r\n", "GET # HTTP/1.1\r\n\r\n", "\r\n\r\n",
                                    "GET  / HTTP/1.1\r\n\r\n", "GET / HTTP/9.9\r\n\r\n", "G(T / HTTP/1.1\r\n\r\n",
                                    "GET /%zz HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n", "GET /%2 HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n",
                                    "GET / HTTP/1.1\r\nno colon\r\n\r\n"}) {
    SCOPED_TRACE(request);
    EXPECT_EQ(status_line(send_request(m_port, request)), "HTTP/1.1 400 Bad Request");
    ASSERT_TRUE(alive());
  }
  EXPECT_EQ(status_line(http_get(m_port, "/")), "HTTP/1.1 200 OK");
  // Heads beyond the bounds: a request line over 2 KiB, a head over 8 KiB.
  EXPECT_EQ(status_line(http_get(m_port, "/" + std::string(3000, 'a'))), "HTTP/1.1 414 URI Too Long");
  EXPECT_EQ(status_line(send_request(m_port, "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nX: " + std::string(9000, 'x') + "\r\n\r\n")),
            "HTTP/1.1 431 Request Header Fields Too Large");
  EXPECT_TRUE(alive());
}

// Before issue 40 one connection that sent nothing blocked every other client (one at a time, no timeout).
TEST_F(CliServe, AnIdleConnectionBlocksNobodyAndTimesOut) {
  const int idle = connect_to(m_port);
  ASSERT_GE(idle, 0);
  ::send(idle, "GET / HT", 8, MSG_NOSIGNAL);  // a head begun and never finished
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(status_line(http_get(m_port, "/")), "HTTP/1.1 200 OK");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2.0);
  // The idle one is answered 408 and closed after 5 s.
  const timeval longer{8, 0};
  ::setsockopt(idle, SOL_SOCKET, SO_RCVTIMEO, &longer, sizeof longer);
  EXPECT_EQ(status_line(receive_all(idle)), "HTTP/1.1 408 Request Timeout");
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GT(waited, 4.0);
  EXPECT_LT(waited, 7.5);
  ::close(idle);
}

// At most 32 connections at once: one more is answered 503 at once, and the server stays up.
TEST_F(CliServe, ConnectionsBeyondTheBoundGet503) {
  std::vector<int> idle;
  for (int i = 0; i < 32; ++i) {
    const int fd = connect_to(m_port);
    ASSERT_GE(fd, 0);
    idle.push_back(fd);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // all 32 accepted
  EXPECT_EQ(status_line(http_get(m_port, "/")), "HTTP/1.1 503 Service Unavailable");
  ::close(idle.back());
  idle.pop_back();
  std::this_thread::sleep_for(std::chrono::milliseconds(400));  // that thread ends after its 200 ms drain
  EXPECT_EQ(status_line(http_get(m_port, "/")), "HTTP/1.1 200 OK");
  for (const int fd : idle) ::close(fd);
  EXPECT_TRUE(alive());
}

// Nothing outside the site's regular files: traversal (plain and percent-encoded), dotfiles, symbolic links
// (to a file inside or outside), folders.
TEST_F(CliServe, OnlyRegularFilesDirectlyInTheFolder) {
  std::ofstream(m_dir / ".secret") << "secret";
  std::filesystem::create_symlink("/etc/passwd", m_dir / "passwd.txt");
  std::filesystem::create_symlink(m_dir / "index.html", m_dir / "link.html");
  std::filesystem::create_directory(m_dir / "sub");
  std::ofstream(m_dir / "sub" / "x.html") << "x";
  std::ofstream(m_dir.parent_path() / "outside.html") << "outside";
  for (const std::string target : {"/../outside.html", "/%2e%2e/outside.html", "/%2E%2E%2Foutside.html", "/./.", "/.",
                                   "/..", "/.secret", "/%2esecret", "/passwd.txt", "/link.html", "/sub", "/sub/x.html",
                                   "/sub%2fx.html", "//etc/passwd", "/index.html%00.js", "/%5c..%5coutside.html"}) {
    SCOPED_TRACE(target);
    EXPECT_EQ(status_line(http_get(m_port, target)), "HTTP/1.1 404 Not Found");
  }
  EXPECT_EQ(status_line(http_get(m_port, "/index.html")), "HTTP/1.1 200 OK");
  EXPECT_EQ(status_line(http_get(m_port, "/%69ndex.html")), "HTTP/1.1 200 OK");  // decoded, then the rules
  EXPECT_TRUE(alive());
}

TEST_F(CliServe, HeadAnswersAndOtherMethodsGet405) {
  const std::string head = http_get(m_port, "/", "HEAD");
  EXPECT_EQ(status_line(head), "HTTP/1.1 200 OK");
  EXPECT_NE(head.find("Content-Length: " + std::to_string(std::filesystem::file_size(m_dir / "index.html")) + "\r\n"),
            std::string::npos) << head;
  EXPECT_EQ(head.size(), head.find("\r\n\r\n") + 4);  // no body
  for (const std::string method : {"POST", "PUT", "DELETE", "OPTIONS"}) {
    const std::string r = http_get(m_port, "/", method);
    EXPECT_EQ(status_line(r), "HTTP/1.1 405 Method Not Allowed") << method;
    EXPECT_NE(r.find("Allow: GET, HEAD\r\n"), std::string::npos) << r;
  }
  // A POST with a body it never reads still gets its whole answer.
  const std::string post = send_request(m_port, "POST / HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 10000\r\n\r\n" +
                                                std::string(10000, 'b'));
  EXPECT_EQ(status_line(post), "HTTP/1.1 405 Method Not Allowed");
}

// The listening socket is bound to 127.0.0.1, not to every address: 127.0.0.2 (also this machine, also the
// loopback device) is refused, as any other address would be.
TEST_F(CliServe, ListensOn127001Only) {
  const int ok = connect_to(m_port, "127.0.0.1");
  EXPECT_GE(ok, 0);
  if (ok >= 0) ::close(ok);
  const int other = connect_to(m_port, "127.0.0.2");
  EXPECT_LT(other, 0);
  if (other >= 0) ::close(other);
}

}  // namespace
}  // namespace shadelab::testing
