// shadelab: the command-line tool. The whole command line, its exit codes and messages are run_cli
// (cli_main.cpp), which the CLI fuzz harness (fuzz/fuzz_cli.cpp) calls too.
#include "cli_common.h"

int main(int argc, char** argv) { return shadelab::cli::run_cli(argc, argv); }
