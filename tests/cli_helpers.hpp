// Test helpers for running the built bkquake program as a subprocess (the way users and
// scripts see it): capture stdout, stderr and the exit status, and make scratch folders
// and scene files that clean themselves up. Header-only so any test file can include it.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace bkq::test {

struct ProcessResult {
  int status = -1;  // exit status; 128 + signal when killed by a signal
  std::string out;  // stdout
  std::string err;  // stderr
  // With a time limit: whether it was reached (SIGTERM sent), and how long the program
  // then took to exit (SIGKILL follows after `kill_after` seconds). With a stop condition
  // (run_bkquake_until): whether it held and SIGTERM was sent, and `hung` when the guard
  // time passed first.
  bool timed_out = false;
  bool hung = false;
  double exit_after_term_s = 0;
  // stderr split into lines (without the newlines).
  std::vector<std::string> err_lines() const {
    std::vector<std::string> lines;
    std::istringstream in(err);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
  }
};

// Runs `program` with `args` (no shell involved, so no quoting worries), optionally in
// `cwd`, and waits for it. stdin is /dev/null. With `timeout_s` > 0 the program gets SIGTERM
// once that many seconds have passed, and SIGKILL `kill_after` seconds later.
// With `stop_when`, the program gets SIGTERM as soon as stop_when() holds (checked every
// few milliseconds: a state the program has reached, not a time), and `timeout_s` is only a
// guard against a hang (SIGTERM, then SIGKILL).
inline ProcessResult run_process(const std::string& program, const std::vector<std::string>& args,
                                 const std::string& cwd = "", double timeout_s = 0,
                                 double kill_after = 5,
                                 const std::function<bool()>& stop_when = nullptr) {
  int out_pipe[2], err_pipe[2];
  if (::pipe(out_pipe) != 0 || ::pipe(err_pipe) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    ::dup2(out_pipe[1], 1);
    ::dup2(err_pipe[1], 2);
    ::close(out_pipe[0]);
    ::close(out_pipe[1]);
    ::close(err_pipe[0]);
    ::close(err_pipe[1]);
    const int devnull = ::open("/dev/null", O_RDONLY);
    if (devnull >= 0) ::dup2(devnull, 0);
    if (!cwd.empty() && ::chdir(cwd.c_str()) != 0) ::_exit(127);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(program.c_str()));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(program.c_str(), argv.data());
    ::_exit(127);
  }
  ::close(out_pipe[1]);
  ::close(err_pipe[1]);
  ProcessResult r;
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  Clock::time_point termed;
  bool killed = false;
  // Past the timeout: SIGTERM, then SIGKILL kill_after seconds later.
  auto enforce_timeout = [&](Clock::time_point now) {
    if (!r.timed_out && stop_when && stop_when()) {
      ::kill(pid, SIGTERM);
      r.timed_out = true;
      termed = now;
      return;
    }
    if (!r.timed_out && now - start >= std::chrono::duration<double>(timeout_s)) {
      r.hung = stop_when != nullptr;
      ::kill(pid, SIGTERM);
      r.timed_out = true;
      termed = now;
    } else if (r.timed_out && !killed &&
               now - termed >= std::chrono::duration<double>(kill_after)) {
      ::kill(pid, SIGKILL);
      killed = true;
    }
  };
  // Read both pipes together so a chatty child cannot block on a full pipe.
  pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
  std::string* sinks[2] = {&r.out, &r.err};
  int open_fds = 2;
  while (open_fds > 0) {
    if (timeout_s > 0) enforce_timeout(Clock::now());
    if (::poll(fds, 2, timeout_s > 0 ? 20 : -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int k = 0; k < 2; ++k) {
      if (fds[k].fd < 0 || !(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      char buf[4096];
      const ssize_t n = ::read(fds[k].fd, buf, sizeof buf);
      if (n > 0) {
        sinks[k]->append(buf, static_cast<std::size_t>(n));
      } else if (n == 0 || errno != EINTR) {
        ::close(fds[k].fd);
        fds[k].fd = -1;
        --open_fds;
      }
    }
  }
  int wstatus = 0;
  // The pipes close when the program exits (or closes them itself): keep the clock going.
  while (true) {
    const pid_t w = ::waitpid(pid, &wstatus, timeout_s > 0 ? WNOHANG : 0);
    if (w == pid || (w < 0 && errno != EINTR)) break;
    if (w == 0) {
      enforce_timeout(Clock::now());
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  if (r.timed_out)
    r.exit_after_term_s = std::chrono::duration<double>(Clock::now() - termed).count();
  r.status = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 128 + WTERMSIG(wstatus);
  return r;
}

// Runs the bkquake binary built alongside the tests.
inline ProcessResult run_bkquake(const std::vector<std::string>& args,
                                 const std::string& cwd = "") {
  return run_process(BKQUAKE_BINARY, args, cwd);
}

// The same with a time limit: SIGTERM after `timeout_s`, SIGKILL `kill_after` s later, so a
// hang fails the test instead of stalling the suite.
inline ProcessResult run_bkquake_for(double timeout_s, const std::vector<std::string>& args,
                                     const std::string& cwd = "", double kill_after = 5) {
  return run_process(BKQUAKE_BINARY, args, cwd, timeout_s, kill_after);
}

// Runs bkquake and sends SIGTERM once `stop_when()` holds (the run has reached a state,
// e.g. written its first checkpoint); `guard_s` only catches a hang (r.hung). After the
// SIGTERM the run has `guard_s` more seconds to write its last checkpoint (a chain of
// millions of blocks takes seconds) before SIGKILL.
inline ProcessResult run_bkquake_until(const std::function<bool()>& stop_when,
                                       const std::vector<std::string>& args, double guard_s = 300) {
  return run_process(BKQUAKE_BINARY, args, "", guard_s, guard_s, stop_when);
}

// Starts bkquake with `args` (in `cwd` when given; stdout and stderr to the file `log`, or
// discarded), sends `sig` once `ready()` turns true (`times` times in a row: a second
// SIGTERM lands while the run is stopping), and returns the exit status (128 + signal when
// killed by one). A run still going after two minutes is killed, so a run that never gets
// ready cannot hang the suite.
template <class Ready>
int run_and_signal_when(const std::vector<std::string>& args, Ready ready, int sig,
                        const std::string& log = "", const std::string& cwd = "", int times = 1) {
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    const int fd =
        ::open(log.empty() ? "/dev/null" : log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    if (!cwd.empty() && ::chdir(cwd.c_str()) != 0) ::_exit(127);
    std::vector<std::string> all = args;
    std::vector<char*> argv{const_cast<char*>(BKQUAKE_BINARY)};
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(BKQUAKE_BINARY, argv.data());
    ::_exit(127);
  }
  int wstatus = 0;
  bool signalled = false;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (::waitpid(pid, &wstatus, WNOHANG) != pid) {
    if (!signalled && ready()) {
      for (int k = 0; k < times; ++k) ::kill(pid, sig);
      signalled = true;
    }
    if (std::chrono::steady_clock::now() > give_up) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &wstatus, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 128 + WTERMSIG(wstatus);
}

// Starts bkquake with `sig` blocked and already pending (the child inherits the mask and
// the pending signal across exec), so the signal arrives at the first moment the program
// unblocks it: a run's stop handler (app/stop_signals.hpp), i.e. before its first event.
// A stop at a known point, with no race against the clock. Output to `log` (or discarded);
// returns the exit status (128 + signal when killed by one).
inline int run_with_pending_signal(const std::vector<std::string>& args, int sig,
                                   const std::string& log = "") {
  sigset_t block, old;
  sigemptyset(&block);
  sigaddset(&block, sig);
  ::sigprocmask(SIG_BLOCK, &block, &old);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    const int fd =
        ::open(log.empty() ? "/dev/null" : log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    ::raise(sig);  // pending: blocked in this process, kept across exec
    std::vector<std::string> all = args;
    std::vector<char*> argv{const_cast<char*>(BKQUAKE_BINARY)};
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(BKQUAKE_BINARY, argv.data());
    ::_exit(127);
  }
  ::sigprocmask(SIG_SETMASK, &old, nullptr);
  int wstatus = 0;
  while (::waitpid(pid, &wstatus, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 128 + WTERMSIG(wstatus);
}

// A fresh scratch folder under the system temp dir, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::string templ = (std::filesystem::temp_directory_path() / "bkquake-test-XXXXXX").string();
    if (!::mkdtemp(templ.data())) throw std::runtime_error("mkdtemp failed");
    path_ = templ;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // path()/name as a string.
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  // Writes `content` to path()/name and returns its path.
  std::string write(const std::string& name, const std::string& content) const {
    const std::string p = file(name);
    std::ofstream(p, std::ios::binary) << content;
    return p;
  }

 private:
  std::filesystem::path path_;
};

// `bkquake run` with a scene's options and then `more`.
inline std::vector<std::string> run_args(const std::vector<std::string>& scene,
                                         const std::vector<std::string>& more) {
  std::vector<std::string> a = {"run"};
  a.insert(a.end(), scene.begin(), scene.end());
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// Whole file as a string (empty when missing).
inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The lines of a summary.json except those a resumed run may write differently from a run
// that never stopped: the writer's provenance (version, revision, time, and the scene's
// origin: the folder's own scene.ini when resumed with it), the wall times and `resumes`.
// Everything else, the status included, must be equal.
inline std::string summary_without_timing(const std::string& json) {
  static const char* const kFields[] = {"\"written\"",
                                        "\"wall_seconds\"",
                                        "\"wall_seconds_total\"",
                                        "\"events_per_second\"",
                                        "\"block_steps_per_second\"",
                                        "\"resumes\"",
                                        "\"git_revision\"",
                                        "\"version\"",
                                        "\"scene\""};
  std::istringstream in(json);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    const auto start = line.find_first_not_of(' ');
    bool skip = false;
    for (const std::string f : kFields)
      skip = skip || (start != std::string::npos && line.compare(start, f.size(), f) == 0);
    if (!skip) out += line + "\n";
  }
  return out;
}

}  // namespace bkq::test
