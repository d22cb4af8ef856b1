#pragma once
// The dabench command line (DESIGN.md, "Command line"): list | solve | run | merge | schedule |
// compare, one file each under apps/cli/.
// Exit status: 0 success, 2 bad input or usage, 3 the algorithm refused the problem
// (skipped), 130 interrupted (rerun with --resume).
namespace dabench {

int cli_main(int argc, char** argv);

}  // namespace dabench
