// The output-folder lock (see folder_lock.hpp). A new lock is written complete into a
// temporary file, flock()ed, and published with link(), which fails if a lock exists: no
// reader ever sees a half-written lock, and a published lock is always flocked. Taking over
// a stale lock flocks the existing file (only one process can) and rewrites its content.
#include "io/folder_lock.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "io/output.hpp"

namespace bkq {

namespace fs = std::filesystem;

namespace {

std::string host_name() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "unknown";
  return buf;
}

// Printable ASCII only, at most 120 characters: the file may be anything, the message not.
std::string printable(const std::string& s) {
  std::string out;
  for (const char c : s)
    if (c >= 0x20 && c < 0x7f && out.size() < 120) out += c;
  return out;
}

LockHolder parse_holder(const std::string& text) {
  LockHolder h;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const auto sp = line.find(' ');
    if (sp == std::string::npos) continue;
    const std::string key = line.substr(0, sp);
    const std::string value = printable(line.substr(sp + 1));
    if (key == "host") h.host = value;
    if (key == "command") h.command = value;
    if (key == "since") h.since = value;
    if (key == "pid") h.pid = std::strtol(value.c_str(), nullptr, 10);
  }
  return h;
}

std::string read_fd(int fd) {
  std::string text;
  char buf[512];
  ssize_t n = 0;
  ::lseek(fd, 0, SEEK_SET);
  while (text.size() < 4096 && (n = ::read(fd, buf, sizeof buf)) > 0)
    text.append(buf, static_cast<std::size_t>(n));
  return text;
}

bool write_fd(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return ::fsync(fd) == 0 || errno == EINVAL;
}

// True when `fd` and `path` are the same file (the lock was not replaced under us).
// (Async-signal-safe: fstat and stat only.)
bool same_file(int fd, const char* path) {
  struct stat a {
  }, b{};
  return ::fstat(fd, &a) == 0 && ::stat(path, &b) == 0 && a.st_dev == b.st_dev &&
         a.st_ino == b.st_ino;
}

// Whether a process still holds the lock open on `fd`: its flock, or where the file
// system has no flock, whether its pid lives (same host only).
bool holder_alive(int fd, const LockHolder& h, bool same_host) {
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return false;
  if (errno == EWOULDBLOCK || errno == EINTR) return true;
  // No flock here (ENOLCK, EINVAL): judge by the pid.
  return same_host && h.pid > 0 && (::kill(static_cast<pid_t>(h.pid), 0) == 0 || errno == EPERM);
}

// The locks this process holds, for the signal handler: fixed storage, no allocation.
constexpr int kMaxHeld = 8;
struct HeldLock {
  volatile sig_atomic_t used = 0;
  int fd = -1;
  char path[4096] = {};
};
HeldLock g_held[kMaxHeld];

void register_held(int fd, const std::string& path) {
  if (path.size() >= sizeof g_held[0].path) return;
  for (HeldLock& h : g_held) {
    if (h.used) continue;
    std::memcpy(h.path, path.c_str(), path.size() + 1);
    h.fd = fd;
    h.used = 1;
    return;
  }
}

void unregister_held(int fd) {
  for (HeldLock& h : g_held)
    if (h.used && h.fd == fd) h.used = 0;
}

// SIGINT, SIGTERM, SIGHUP at their default action while a lock is held: remove the locks,
// then end by the same signal (exit status 128 + signal, as before).
void release_and_die(int sig) {
  release_folder_locks_from_signal();
  static const char msg[] = "bkquake: stopped by a signal; the output folder's lock is released\n";
  [[maybe_unused]] const ssize_t n = ::write(2, msg, sizeof msg - 1);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void install_release_handlers() {
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;
    struct sigaction sa {};
    sa.sa_handler = release_and_die;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    ::sigaction(sig, &sa, nullptr);
  }
}

// Holds SIGINT, SIGTERM and SIGHUP back while the lock is being taken: a signal between the
// lock file's creation and the release handler's installation would otherwise end the
// process by its default action and leave the lock behind. On leaving, a signal held back is
// delivered to the handler, which removes the lock.
class SignalsHeldBack {
 public:
  SignalsHeldBack() {
    sigset_t set;
    sigemptyset(&set);
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&set, sig);
    ::pthread_sigmask(SIG_BLOCK, &set, &old_);
  }
  ~SignalsHeldBack() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  SignalsHeldBack(const SignalsHeldBack&) = delete;
  SignalsHeldBack& operator=(const SignalsHeldBack&) = delete;

 private:
  sigset_t old_{};
};

}  // namespace

void release_folder_locks_from_signal() noexcept {
  for (HeldLock& h : g_held) {
    if (!h.used) continue;
    if (same_file(h.fd, h.path)) ::unlink(h.path);
    h.used = 0;
  }
}

std::string LockHolder::describe() const {
  if (host.empty() || pid <= 0) return "an unknown process (the lock file is garbled)";
  return "bkquake " + (command.empty() ? std::string("?") : command) + " (pid " +
         std::to_string(pid) + " on host " + host + (since.empty() ? "" : ", since " + since) + ")";
}

FolderLock::FolderLock(const std::string& dir, const std::string& command, StaleLock stale)
    : path_((fs::path(dir) / kFileName).string()) {
  const SignalsHeldBack held_back;
  const std::string me = host_name();
  const std::string content = "bkquake folder lock\nhost " + me + "\npid " +
                              std::to_string(::getpid()) + "\ncommand " + command + "\nsince " +
                              utc_now_iso() + "\n";
  // A few rounds: a lock released (unlinked) between our attempts sends us round again.
  for (int round = 0; round < 5; ++round) {
    std::string tmp = (fs::path(dir) / (std::string(kTemporaryPrefix) + "XXXXXX")).string();
    const int fd = ::mkstemp(tmp.data());
    if (fd < 0) throw Error("cannot write to output folder '" + dir + "': " + std::strerror(errno));
    ::fchmod(fd, 0644);
    const bool ok = write_fd(fd, content) && ::flock(fd, LOCK_EX | LOCK_NB) == 0;
    const int err = errno;
    int linked = ok ? ::link(tmp.c_str(), path_.c_str()) : -1;
    int link_err = errno;
    if (ok && linked != 0 && (link_err == EPERM || link_err == EOPNOTSUPP)) {
      // No hard links here (some FUSE and FAT mounts): create the lock in place; a reader
      // may then see it empty for a moment, which reads as "an unknown process".
      const int direct = ::open(path_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
      link_err = errno;
      if (direct >= 0) {
        linked = ::flock(direct, LOCK_EX | LOCK_NB) == 0 && write_fd(direct, content) ? 0 : -1;
        link_err = errno;
        if (linked == 0) {
          ::unlink(tmp.c_str());
          ::close(fd);
          fd_ = direct;
          held();
          return;
        }
        ::unlink(path_.c_str());
        ::close(direct);
      }
    }
    ::unlink(tmp.c_str());
    if (!ok) {
      ::close(fd);
      // Another bkquake holding this folder's lock was probing our temporary for staleness
      // (remove_stale_temporaries) at the moment we took its flock: go round.
      if (err == EWOULDBLOCK) continue;
      throw Error("cannot write to output folder '" + dir + "': " + std::strerror(err));
    }
    if (linked == 0) {
      fd_ = fd;
      held();
      return;
    }
    ::close(fd);
    // Our temporary went before it was linked (a holder removed it as stale in the moment
    // before our flock, see remove_stale_temporaries): go round and find that holder.
    if (link_err == ENOENT) continue;
    if (link_err != EEXIST)
      throw Error("cannot create the lock file '" + path_ + "': " + std::strerror(link_err));

    // A lock exists: whose, and is it alive?
    const int old = ::open(path_.c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW);
    if (old < 0) {
      if (errno == ENOENT) continue;  // released meanwhile
      // No bkquake writes its lock as a symbolic link: it is replaced (taking over), never
      // written through.
      if (errno == ELOOP && stale == StaleLock::TakeOver && ::unlink(path_.c_str()) == 0) continue;
      if (errno == ELOOP)
        throw Error("the lock file '" + path_ +
                    "' is a symbolic link, which no bkquake writes; remove it, or use --force");
      throw Error("cannot open the lock file '" + path_ + "': " + std::strerror(errno));
    }
    const LockHolder h = parse_holder(read_fd(old));
    const bool same_host = h.host == me;
    if (holder_alive(old, h, same_host)) {
      ::close(old);
      // The file still names a process that is gone: another bkquake has just flocked the
      // stale lock and is rewriting it (it won the race to take it over).
      const bool named_gone =
          same_host && h.pid > 0 && ::kill(static_cast<pid_t>(h.pid), 0) != 0 && errno == ESRCH;
      if (named_gone)
        throw Error("output folder '" + dir + "' is in use: another bkquake is taking over the " +
                    "stale lock of " + h.describe() +
                    ", which is gone; wait for it to finish or choose another --out");
      throw Error("output folder '" + dir + "' is in use by " + h.describe() +
                  "; wait for it to finish or choose another --out");
    }
    if (!same_file(old, path_.c_str())) {  // released and replaced between open and flock
      ::close(old);
      continue;
    }
    if (!same_host && !h.host.empty()) {
      ::close(old);
      throw Error("output folder '" + dir + "' is locked by " + h.describe() +
                  "; a lock of another host is never taken over: if that run is gone, delete '" +
                  path_ + "' by hand");
    }
    if (stale == StaleLock::Refuse) {
      ::close(old);
      throw Error("output folder '" + dir + "' holds the stale lock of " + h.describe() +
                  ", which is gone (killed?); use --resume to continue its run or --force to "
                  "start over");
    }
    // We hold the flock of the stale file: nobody else can take it over now. One with other
    // names (a hard link to a file elsewhere) is replaced, never rewritten in place.
    struct stat st {};
    if (::fstat(old, &st) == 0 && st.st_nlink > 1 && ::unlink(path_.c_str()) == 0) {
      ::close(old);
      continue;
    }
    if (::ftruncate(old, 0) != 0 || !write_fd(old, content)) {
      const int e = errno;
      ::close(old);
      throw Error("cannot rewrite the lock file '" + path_ + "': " + std::strerror(e));
    }
    std::fprintf(stderr,
                 "bkquake: warning: taking over the stale lock of '%s' left by %s, which is gone\n",
                 dir.c_str(), h.describe().c_str());
    fd_ = old;
    held();
    return;
  }
  throw Error("cannot take the lock '" + path_ + "': it keeps changing under us");
}

void FolderLock::held() {
  register_held(fd_, path_);
  install_release_handlers();
  remove_stale_temporaries(fs::path(path_).parent_path().string());
}

void FolderLock::remove_stale_temporaries(const std::string& dir) {
  // A process killed between creating its temporary and unlinking it (above) leaves it. A
  // live one holds its temporary's flock from the write on, so one whose flock we can take
  // is stale. (In the few microseconds before a racing process takes its flock, its
  // temporary may go: it then fails to link with 'No such file' instead of finding our lock,
  // and fails either way.)
  std::error_code ec;
  std::vector<std::string> candidates;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.path().filename().string().rfind(kTemporaryPrefix, 0) == 0)
      candidates.push_back(entry.path().string());
  for (const std::string& f : candidates) {
    const int fd = ::open(f.c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0) continue;
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0 && same_file(fd, f.c_str())) ::unlink(f.c_str());
    ::close(fd);
  }
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  unregister_held(fd_);
  if (same_file(fd_, path_.c_str())) ::unlink(path_.c_str());
  ::close(fd_);
}

std::optional<LockHolder> read_folder_lock(const std::string& dir) {
  const std::string path = (fs::path(dir) / FolderLock::kFileName).string();
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  const LockHolder h = parse_holder(read_fd(fd));
  ::close(fd);
  return h;
}

}  // namespace bkq
