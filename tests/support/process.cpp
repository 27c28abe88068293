#include "process.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>

#include <csignal>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace bhnsid::test {

namespace fs = std::filesystem;

namespace {

double now_seconds() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// In the child: stdout and stderr, the working directory, the file-size limit, then exec.
[[noreturn]] void exec_child(const fs::path& program, const std::vector<std::string>& args, const fs::path& out_file,
                             const fs::path& err_file, const fs::path& cwd, long file_size_limit, Stdout mode) {
  int out = -1;
  if (mode == Stdout::closed_pipe) {
    int fds[2];
    if (::pipe(fds) != 0) ::_exit(125);
    ::close(fds[0]);  // nobody will ever read: every write fails with EPIPE (or SIGPIPE)
    out = fds[1];
  } else {
    out = ::open(mode == Stdout::dev_full ? "/dev/full" : out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  const int err = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ::dup2(out, 1);
  ::dup2(err, 2);
  if (!cwd.empty() && ::chdir(cwd.c_str()) != 0) ::_exit(126);
  if (file_size_limit > 0) {
    rlimit limit{static_cast<rlim_t>(file_size_limit), static_cast<rlim_t>(file_size_limit)};
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }
  // The test runner's own signal dispositions must not leak into the child.
  ::signal(SIGPIPE, SIG_DFL);
  std::vector<char*> argv;
  std::string exe = program.string();
  argv.push_back(exe.data());
  std::vector<std::string> copies = args;
  for (auto& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  ::execv(exe.c_str(), argv.data());
  ::_exit(127);
}

ProcessResult collect(int status, const rusage& usage, const fs::path& out_file, const fs::path& err_file) {
  ProcessResult result;
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  result.max_rss_kib = usage.ru_maxrss;
  result.out = read_file(out_file);
  result.err = read_file(err_file);
  return result;
}

}  // namespace

ProcessResult run_bhnsid(const std::vector<std::string>& args, const fs::path& cwd, long file_size_limit, Stdout mode) {
  return run_program(BHNSID_EXE, args, cwd, file_size_limit, mode);
}

ProcessResult run_program(const fs::path& program, const std::vector<std::string>& args, const fs::path& cwd,
                          long file_size_limit, Stdout mode) {
  TempDir capture;
  const fs::path out_file = capture.path() / "out", err_file = capture.path() / "err";
  const double start = now_seconds();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) exec_child(program, args, out_file, err_file, cwd, file_size_limit, mode);
  int status = 0;
  rusage usage{};
  ::wait4(pid, &status, 0, &usage);
  ProcessResult result = collect(status, usage, out_file, err_file);
  result.seconds = now_seconds() - start;
  return result;
}

Background::Background(const std::vector<std::string>& args, const fs::path& cwd) {
  std::string templ = (fs::temp_directory_path() / "bhnsid-bg-XXXXXX").string();
  if (!::mkdtemp(templ.data())) throw std::runtime_error("mkdtemp failed");
  capture_ = templ;
  start_ = now_seconds();
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error("fork failed");
  if (pid_ == 0) exec_child(BHNSID_EXE, args, capture_ / "out", capture_ / "err", cwd, 0, Stdout::captured);
}

Background::~Background() {
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
  }
  std::error_code ec;
  fs::remove_all(capture_, ec);
}

void Background::signal(int sig) const {
  if (pid_ > 0) ::kill(pid_, sig);
}

ProcessResult Background::wait(double timeout_seconds) {
  int status = 0;
  rusage usage{};
  bool killed = false;
  for (;;) {
    const pid_t r = ::wait4(pid_, &status, WNOHANG, &usage);
    if (r == pid_) break;
    if (r < 0) throw std::runtime_error("wait4 failed");
    if (now_seconds() - start_ > timeout_seconds && !killed) {
      ::kill(pid_, SIGKILL);
      killed = true;
    }
    ::usleep(10000);
  }
  pid_ = -1;
  ProcessResult result = collect(status, usage, capture_ / "out", capture_ / "err");
  result.seconds = now_seconds() - start_;
  if (killed) result.err += "\n[test: killed after the timeout]\n";
  return result;
}

bool wait_for_text(const fs::path& path, const std::string& text, double timeout_seconds) {
  const double start = now_seconds();
  while (now_seconds() - start < timeout_seconds) {
    std::error_code ec;
    if (fs::exists(path, ec) && (text.empty() || read_file(path).find(text) != std::string::npos)) return true;
    ::usleep(10000);
  }
  return false;
}

TempDir::TempDir() {
  std::string templ = (fs::temp_directory_path() / "bhnsid-test-XXXXXX").string();
  if (!::mkdtemp(templ.data())) throw std::runtime_error("mkdtemp failed");
  path_ = templ;
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

fs::path TempDir::write(const std::string& name, const std::string& contents) const {
  const fs::path p = path_ / name;
  std::ofstream(p, std::ios::binary) << contents;
  return p;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path source_dir() { return BHNSID_SOURCE_DIR; }
fs::path test_plugin_dir() { return BHNSID_TEST_PLUGIN_DIR; }

}  // namespace bhnsid::test
