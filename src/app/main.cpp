#include "app/cli.hpp"

int main(int argc, char** argv) { return gf::app::runCommandLine(argc, argv); }
