#include "apps/cli.hpp"

int main(int argc, char** argv) { return dabench::cli_main(argc, argv); }
