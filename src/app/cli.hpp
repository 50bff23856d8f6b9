#pragma once

namespace gf::app {
/// Parses the command line and runs the chosen command; returns the process exit code.
int runCommandLine(int argc, char** argv);
}
