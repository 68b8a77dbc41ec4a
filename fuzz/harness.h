// Shared pieces of shadelab's fuzz harnesses (fuzz/README.md). Each fuzz_<name>.cpp defines
// LLVMFuzzerTestOneInput for one parser; it is linked with libFuzzer in the fuzz preset and with
// replay_main.cpp in the ordinary build, where CTest replays the seed corpus and every saved regression input.
//
// A harness checks the parser's contract, not only that it survives: an error must be one printable line that
// names the file (core/text.h), a success must satisfy the documented invariants. A broken contract is a
// finding: the harness prints what broke and aborts, which libFuzzer saves as a crash.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>

namespace shadelab::fuzz {

// A private folder for the files a harness writes ($TMPDIR/shadelab-fuzz-<name>-<pid>), made on first use
// and removed at exit.
const std::filesystem::path& work_dir(std::string_view name);

void write_file(const std::filesystem::path& path, std::string_view bytes);
std::string_view as_text(const std::uint8_t* data, std::size_t size);

// One input that holds two files: the bytes before the first separator line and those after it (empty
// when there is none). The OBJ harness uses it for the OBJ and its mtllib, the glTF harnesses for the
// JSON (or GLB) and an external buffer.
inline constexpr std::string_view file_separator = "\n#--shadelab-fuzz-next-file--\n";
std::pair<std::string_view, std::string_view> split_files(std::string_view input);

// A finding: prints "shadelab fuzz finding: <what>: <detail>" on stderr and aborts.
[[noreturn]] void finding(std::string_view what, std::string_view detail);

// The message contract (docs/testing.md, "Classes of bad input"): one line, no control or invalid UTF-8
// bytes (they are escaped as \xNN), at most `max_bytes`, containing `must_contain` (a file name) unless
// it is empty.
void require_one_line(std::string_view message, std::string_view must_contain, std::size_t max_bytes = 2000);

}  // namespace shadelab::fuzz
