// rrc-accumulate: EXR sequence in, accumulated EXR sequence out.  See --help.
#include "accumulate.h"

#include <iostream>

int main(int argc, char** argv)
{
    return rrc_cli::accumulate_main(argc, argv, std::cout, std::cerr);
}
