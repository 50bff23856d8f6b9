#pragma once
// Command-line entry: grainflow run | check | bench | docs | --version.

namespace gf::app {

/// Exit codes (documented in the README).
enum ExitCode : int {
  kExitOk = 0,
  kExitInvalidCase = 1,     // case file missing, not YAML, wrong key/type/range/model, inconsistent
  kExitUsage = 2,           // bad command line
  kExitDiverged = 3,        // NaN/Inf, particle left the domain, CFL blow-up
  kExitCheckpoint = 4,      // corrupt, truncated or mismatched checkpoint
  kExitIo = 5,              // output directory not writable, refusing to overwrite, write failure
  kExitInterrupted = 130,   // SIGINT/SIGTERM (a checkpoint was written)
};

/// Parses the command line and runs the chosen command; returns the process exit code.
int runCommandLine(int argc, char** argv);

}  // namespace gf::app
