// dabench's command line with this project's algorithms added: `./outside list` shows
// damped-bp beside the built-in algorithms, `./outside run quickstart-damped.ini` runs it.
// cli_main is the whole `dabench` program (list | solve | run); the registrations of
// damped_bp.cpp, linked into this program, are what it adds.
#include "apps/cli.hpp"

int main(int argc, char** argv) { return dabench::cli_main(argc, argv); }
