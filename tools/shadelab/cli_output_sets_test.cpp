// Issue 40, findings 5, 7 and 8: outputs that belong together are published together (write_files_atomically,
// docs/design.md "Output sets"), files of an older output of the same name are not left mixed in, concurrent
// writers are serialised, temporaries of dead runs are removed, every output is checked writable before the
// work, and an overflowing light conversion is an error.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;
using shadelab::testing::constant_hdr;
using shadelab::testing::run;
using shadelab::testing::temp_dir;

// 40 x 24, 16 spp (tests/scale-out/scene.json).
const std::string scene = std::string(SHADELAB_SCENES_DIR) + "/../tests/scale-out/scene.json";

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = temp_dir() / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// One line on stderr, exit 2, the line holding `needle`.
void expect_one_line_error(const shadelab::testing::CliRun& r, const std::string& needle) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
}

// Finding 5: a smaller chain written over a larger one left the old deeper levels beside the new ones, exit 0.
TEST(CliOutputSets, SmallerSpecularChainLeavesNoDeeperLevelsOfTheOlderOne) {
  const fs::path dir = fresh_dir("chain");
  const fs::path out = dir / "s.ktx2";
  ASSERT_EQ(run("bake specular " + constant_hdr().string() + " --size 16 --exr-faces --out " + out.string()).code, 0);
  EXPECT_TRUE(fs::exists(dir / "s_m4_pz.exr"));
  std::ofstream(dir / "s_notes.txt") << "not a face";  // not of the chain's naming: stays
  std::ofstream(dir / "t_m0_px.exr") << "another chain's face";
  const auto r = run("bake specular " + constant_hdr().string() + " --size 4 --exr-faces --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  std::vector<std::string> want = {"s.ktx2", "s_notes.txt", "t_m0_px.exr"};
  for (int m = 0; m < 3; ++m) {
    for (const char* f : {"nx", "ny", "nz", "px", "py", "pz"}) want.push_back("s_m" + std::to_string(m) + "_" + f + ".exr");
  }
  std::sort(want.begin(), want.end());
  EXPECT_EQ(listing(dir), want);
  // --no-exr-faces: the container alone is the output; the older faces go. The default is the same.
  ASSERT_EQ(run("bake specular " + constant_hdr().string() + " --size 4 --no-exr-faces --out " + out.string()).code, 0);
  EXPECT_EQ(listing(dir), (std::vector<std::string>{"s.ktx2", "s_notes.txt", "t_m0_px.exr"}));
  ASSERT_EQ(run("bake specular " + constant_hdr().string() + " --size 4 --exr-faces --out " + out.string()).code, 0);
  ASSERT_EQ(run("bake specular " + constant_hdr().string() + " --size 4 --out " + out.string()).code, 0);
  EXPECT_EQ(listing(dir), (std::vector<std::string>{"s.ktx2", "s_notes.txt", "t_m0_px.exr"}));
}

// Finding 5: a face that cannot be written part-way left exit 2 with the new container, new level-0 faces and
// the old chain's other faces. Now nothing of the old chain changes (here the face is refused before the work;
// the library test ImageIo.WriteFilesAtomicallyFailingPartWayChangesNothing fails the write itself).
TEST(CliOutputSets, SpecularChainThatCannotBeWrittenChangesNothing) {
  const fs::path dir = fresh_dir("chain_fail");
  const fs::path out = dir / "s.ktx2";
  ASSERT_EQ(run("bake specular " + constant_hdr().string() + " --size 4 --lobe ggx --exr-faces --out " + out.string()).code, 0);
  const std::string old_container = bytes(out), old_face = bytes(dir / "s_m0_px.exr");
  fs::remove(dir / "s_m1_px.exr");
  fs::create_directories(dir / "s_m1_px.exr");  // in the way of a level-1 face
  const auto before = listing(dir);
  const auto r = run("bake specular " + constant_hdr().string() + " --size 4 --exr-faces --out " + out.string());
  expect_one_line_error(r, "s_m1_px.exr");
  EXPECT_EQ(bytes(out), old_container);
  EXPECT_EQ(bytes(dir / "s_m0_px.exr"), old_face);
  EXPECT_EQ(listing(dir), before);
}

// Finding 7: `bake ibl` over a folder that holds an older bake with the other container, and the temporaries
// of dead runs (a kill -9 between the renames, before output sets): the older cubes go (the manifest names only
// the new ones) and so do the temporaries, whatever target they were for.
TEST(CliOutputSets, BakeIblLeavesNoOlderContainerAndNoStaleTemporaries) {
  const fs::path dir = fresh_dir("ibl");
  const std::string base = "bake ibl " + constant_hdr().string() + " --size 4 --irradiance-size 4 --dfg-size 4 --out-dir " +
                           dir.string();
  ASSERT_EQ(run(base + " --container dds").code, 0);
  ASSERT_TRUE(fs::exists(dir / "specular.dds"));
  for (const char* stale : {".specular.dds.tmp-4194999-0-1", ".irradiance.ktx2.tmp-4194999-3-9-backup-1",
                            ".sh9.json.set-4194999-0-1.tmp", ".manifest.json.set-4194999-0-1.old"}) {
    std::ofstream(dir / stale) << "left by a dead run";
  }
  const auto r = run(base + " --container ktx2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listing(dir), (std::vector<std::string>{"dfg.ktx2", "irradiance.ktx2", "manifest.json", "sh9.json",
                                                    "specular.ktx2", "split_sum_lobes.json"}));
}

// Finding 7: two concurrent merges of different renders into the same --out/--png left a mixed pair (6 of 10
// rounds, exit 0). The writers are serialised on the folder's lock: every round ends with one render's pair.
TEST(CliOutputSets, ConcurrentMergesIntoOneOutputNeverMix) {
  const fs::path dir = fresh_dir("merge");
  std::string parts[2];
  for (int k = 0; k < 2; ++k) {
    const std::string tag = k == 0 ? "a" : "b";
    for (int i = 0; i < 2; ++i) {
      const fs::path p = dir / (tag + std::to_string(i) + ".exr");
      const auto r = run("render " + scene + " --spp " + std::to_string(4 + 4 * k) + " --shard " + std::to_string(i) +
                         "/2 --threads 1 --out " + p.string());
      ASSERT_EQ(r.code, 0) << r.err;
      parts[k] += " " + p.string();
    }
    ASSERT_EQ(run("merge" + parts[k] + " --out " + (dir / (tag + ".exr")).string() + " --png " +
                  (dir / (tag + ".png")).string()).code, 0);
  }
  const std::string want_exr[2] = {bytes(dir / "a.exr"), bytes(dir / "b.exr")};
  const std::string want_png[2] = {bytes(dir / "a.png"), bytes(dir / "b.png")};
  ASSERT_NE(want_exr[0], want_exr[1]);
  ASSERT_NE(want_png[0], want_png[1]);
  const fs::path out = dir / "out" / "x.exr", png = dir / "out" / "x.png";
  fs::create_directories(out.parent_path());
  int mixed = 0;
  for (int round = 0; round < 12; ++round) {
    std::string cmd = "bash -c '";
    for (int k = 0; k < 2; ++k) {
      cmd += std::string(SHADELAB_EXE) + " merge" + parts[k] + " --out " + out.string() + " --png " + png.string() +
             " >/dev/null & ";
    }
    cmd += "wait'";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    const std::string e = bytes(out), p = bytes(png);
    const bool a = e == want_exr[0] && p == want_png[0], b = e == want_exr[1] && p == want_png[1];
    if (!a && !b) ++mixed;
  }
  EXPECT_EQ(mixed, 0) << "rounds that ended with the EXR of one merge and the PNG of the other";
  EXPECT_EQ(listing(out.parent_path()), (std::vector<std::string>{"x.exr", "x.png"}));
}

// Finding 7: kill -9 during `merge --out X.exr --png X.png` left a new EXR beside an old PNG. Killed at any time,
// the pair is whole once the next writer into the folder has run (it completes a committed set, removes the
// temporaries of one that was not).
TEST(CliOutputSets, KillDuringMergeNeverLeavesAMixedPairBehind) {
  const fs::path dir = fresh_dir("kill");
  std::string parts[2];
  for (int k = 0; k < 2; ++k) {
    for (int i = 0; i < 2; ++i) {
      const fs::path p = dir / ((k == 0 ? "a" : "b") + std::to_string(i) + ".exr");
      ASSERT_EQ(run("render " + scene + " --spp " + std::to_string(4 + 4 * k) + " --shard " + std::to_string(i) +
                    "/2 --threads 1 --out " + p.string()).code, 0);
      parts[k] += " " + p.string();
    }
  }
  const fs::path out = dir / "out" / "x.exr", png = dir / "out" / "x.png";
  fs::create_directories(out.parent_path());
  ASSERT_EQ(run("merge" + parts[0] + " --out " + out.string() + " --png " + png.string()).code, 0);
  const std::string exr_a = bytes(out), png_a = bytes(png);
  ASSERT_EQ(run("merge" + parts[1] + " --out " + out.string() + " --png " + png.string()).code, 0);
  const std::string exr_b = bytes(out), png_b = bytes(png);
  for (int round = 0; round < 16; ++round) {
    // Alternate the renders so that each kill lands on a real change; kill after 0 .. 30 ms.
    char delay[16];
    std::snprintf(delay, sizeof delay, "0.%03d", (round * 7) % 31);
    const std::string cmd = "bash -c '" + std::string(SHADELAB_EXE) + " merge" + parts[(round + 1) % 2] + " --out " +
                            out.string() + " --png " + png.string() + " >/dev/null 2>&1 & pid=$!; sleep " + delay +
                            "; kill -9 $pid 2>/dev/null; wait $pid; true'";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    ASSERT_EQ(run("bake dfg --size 2 --out " + (out.parent_path() / "next.exr").string()).code, 0);  // the next writer
    const std::string e = bytes(out), p = bytes(png);
    EXPECT_TRUE((e == exr_a && p == png_a) || (e == exr_b && p == png_b)) << "round " << round;
    EXPECT_EQ(listing(out.parent_path()), (std::vector<std::string>{"next.exr", "x.exr", "x.png"})) << "round " << round;
  }
}

// Finding 8: a missing output folder was reported only after the whole render or bake had run. Every command
// now checks that each output can be written before its work: one line naming the option, the file and the
// folder, exit 2.
TEST(CliOutputSets, UnwritableOutputsAreRefusedBeforeTheWork) {
  const fs::path dir = fresh_dir("writable");
  const std::string missing = (dir / "missing").string();
  const std::string hdr = constant_hdr().string();
  std::ofstream(dir / "file.txt") << "a file, not a folder";
  const std::string part = (dir / "file.txt").string();  // an input that exists (merge reads it only later)
  const std::string under_file = (dir / "file.txt" / "sub").string();
  struct Case {
    std::string args, needle;
  };
  const std::vector<Case> cases = {
      {"render " + scene + " --out " + missing + "/x.exr", "the folder '" + missing + "' does not exist"},
      {"render " + scene + " --out " + dir.string() + "/x.exr --png " + missing + "/x.png", "--png"},
      {"merge " + part + " --out " + missing + "/x.exr", "the folder '" + missing + "' does not exist"},
      {"bake specular " + hdr + " --out " + missing + "/s.ktx2", "the folder '" + missing + "' does not exist"},
      {"bake irradiance " + hdr + " --out " + missing + "/i.ktx2", "the folder '" + missing + "' does not exist"},
      {"bake convert " + hdr + " --out " + missing + "/c.exr", "the folder '" + missing + "' does not exist"},
      {"bake sh " + hdr + " --out " + missing + "/sh.json", "the folder '" + missing + "' does not exist"},
      {"bake dfg --size 4 --out " + missing + "/d.exr", "the folder '" + missing + "' does not exist"},
      {"bake ibl " + hdr + " --out-dir " + under_file, "is not a folder"},
      {"ibl-error " + hdr + " --out " + under_file, "is not a folder"},
      {"report " + scene + " --spp 1 --out " + under_file, "is not a folder"},
      {"plot fv --out " + missing + "/fv.svg", "the folder '" + missing + "' does not exist"},
      {"plot fv --out " + dir.string() + "/fv.svg --csv " + missing + "/fv.csv", "--csv"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    expect_one_line_error(run(c.args), c.needle);
  }
  EXPECT_EQ(listing(dir), std::vector<std::string>{"file.txt"});
}

// Finding 8: `light 1e308 --from game --to W/m2` printed inf with exit 0.
TEST(CliOutputSets, OverflowingLightConversionIsAnError) {
  expect_one_line_error(run("light 1e308 --from game --to W/m2"), "overflows");
  expect_one_line_error(run("light 1e308,1,1 --from game --to W/m2 --json"), "overflows");
  const auto ok = run("light 1e300 --from game --to W/m2");  // (1e307: its 683 x Y lux overflows, also an error)
  EXPECT_EQ(ok.code, 0) << ok.err;
}

// Messages that named the wrong thing (issue 40, finding 8): an unknown unit was "light: unknown unit 'x'"
// whichever option gave it; a bad --ibl file of shader verify was said as "--ibl: bake ibl FILE: ...", a
// command the user never typed.
TEST(CliOutputSets, BadUnitsAndIblFilesNameTheirOption) {
  const auto one_line = [](const shadelab::testing::CliRun& r) {
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    return r.err.rfind("shadelab: ", 0) == 0 ? r.err.substr(10, r.err.size() - 11) : r.err;
  };
  EXPECT_EQ(one_line(run("light 1 --from x --to lux")), "--from: unknown unit 'x' (units: shadelab light --list)");
  EXPECT_EQ(one_line(run("light 1 --from game --to luxx --json")),
            "--to: unknown unit 'luxx' (units: shadelab light --list)");
  const fs::path dir = fresh_dir("ibl_message");
  const fs::path not_an_image = dir / "notes.txt";
  std::ofstream(not_an_image) << "not an image\n";
  const std::string line = one_line(run("shader verify ggx --lang glsl --ibl " + not_an_image.string()));
  EXPECT_EQ(line.rfind("--ibl: ", 0), 0u) << line;
  EXPECT_EQ(line.find("bake ibl"), std::string::npos) << line;
  EXPECT_NE(line.find(not_an_image.string()), std::string::npos) << line;
}

}  // namespace
