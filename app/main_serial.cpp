// `anitet`: the command-line tool (app/main.cpp), one process.
#include "commands.hpp"

int main(int argc, char** argv) { return anitet::cli::cli_main(argc, argv); }
