#pragma once
// Runs the grainflow executable as a user would and captures its exit code and output.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace gf::testing {

struct CommandResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

inline CommandResult runShell(const std::string& command) {
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) result.output += buffer.data();
  const int status = ::pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

inline CommandResult grainflow(const std::string& arguments) {
  return runShell(std::string(GRAINFLOW_BINARY) + " " + arguments);
}

/// grainflow under `mpirun -n ranks` (root-safe, one OpenMP thread per rank, ranks that yield when idle:
/// more ranks than cores).
inline CommandResult grainflowOnRanks(int ranks, const std::string& arguments) {
  return runShell(
      "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 OMPI_MCA_mpi_yield_when_idle=1 "
      "mpirun --oversubscribe -n " + std::to_string(ranks) + " " + std::string(GRAINFLOW_BINARY) + " " + arguments);
}

/// A fresh empty directory under the system temp dir, removed by the destructor.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() / ("grainflow_test_" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& content) const {
    std::ofstream(file(name)) << content;
    return file(name);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The grainflow executable started in the background with `arguments` (stdout and stderr to
/// `logFile`), for tests that watch a run while it goes. The destructor kills it if it still runs.
class BackgroundGrainflow {
 public:
  BackgroundGrainflow(const std::vector<std::string>& arguments, const std::string& logFile) {
    std::vector<std::string> words{GRAINFLOW_BINARY};
    words.insert(words.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t files;
    ::posix_spawn_file_actions_init(&files);
    ::posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, logFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::posix_spawn_file_actions_adddup2(&files, STDOUT_FILENO, STDERR_FILENO);
    if (::posix_spawn(&pid_, argv[0], &files, nullptr, argv.data(), environ) != 0) pid_ = -1;
    ::posix_spawn_file_actions_destroy(&files);
  }
  ~BackgroundGrainflow() {
    if (running()) {
      ::kill(pid_, SIGKILL);
      wait();
    }
  }
  BackgroundGrainflow(const BackgroundGrainflow&) = delete;
  BackgroundGrainflow& operator=(const BackgroundGrainflow&) = delete;

  bool started() const { return pid_ > 0; }
  /// Still running (not yet exited and reaped).
  bool running() {
    if (pid_ <= 0 || exited_) return false;
    int status = 0;
    const pid_t done = ::waitpid(pid_, &status, WNOHANG);
    if (done == 0) return true;
    record(done == pid_ ? status : -1);
    return false;
  }
  void signal(int sig) const {
    if (pid_ > 0 && !exited_) ::kill(pid_, sig);
  }
  /// Waits for the exit; the exit code, or -1 if a signal ended the process.
  int wait() {
    if (pid_ > 0 && !exited_) {
      int status = 0;
      record(::waitpid(pid_, &status, 0) == pid_ ? status : -1);
    }
    return exitCode_;
  }

 private:
  void record(int status) {  // (-1: waitpid failed)
    exited_ = true;
    exitCode_ = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  pid_t pid_ = -1;
  bool exited_ = false;
  int exitCode_ = -1;
};

inline std::string sourcePath(const std::string& relative) { return std::string(GRAINFLOW_SOURCE_DIR) + "/" + relative; }

}  // namespace gf::testing
