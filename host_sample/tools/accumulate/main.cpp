// rrc-accumulate: EXR sequence in, accumulated EXR sequence out.  See --help.
#include "accumulate.h"

#include <iostream>

#if defined(__unix__) || defined(__APPLE__)
#    include <unistd.h>
static bool stdout_is_terminal() { return isatty(STDOUT_FILENO) != 0; }
#else
static bool stdout_is_terminal() { return false; }
#endif

int main(int argc, char** argv) { return rrc_cli::accumulate_main(argc, argv, std::cout, std::cerr, stdout_is_terminal()); }
