// SIGINT and SIGTERM during a run (event or continuous). The first asks the run to stop
// at the next point it can (after the current event or time step: checkpoint, flush, exit
// 128 + signal); a second one exits at once, leaving the last checkpoint intact
// (checkpoints are renamed into place atomically) and removing the folder's lock. So does
// the first one when the run has not reached such a point kStopGraceSeconds later (an event
// of a wide stencil over a long chain can take minutes): every signal is honoured within
// that time, whatever loop the run is in. Once the run has left its loop (stopping():
// writing its checkpoint, which may take seconds for a long chain) nothing cuts it short
// but a second signal. The grace is kept by a thread of its own, woken by the handler
// (sem_post is async-signal-safe), not by SIGALRM, so a caller's own alarm (a Python
// program's signal.alarm) is left alone. Runs at once in one process (friction-study's
// threads) share one grace thread; the first of them to leave its loop ends the grace for
// all (they then stop after their current event, as before the grace existed).
#pragma once

#include <pthread.h>
#include <semaphore.h>
#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

#include "io/folder_lock.hpp"

namespace bkq {

// How long the first signal waits for the run to reach a point where it can stop.
inline constexpr unsigned kStopGraceSeconds = 10;

namespace detail {
inline volatile std::sig_atomic_t g_stop_signal = 0;
inline volatile std::sig_atomic_t g_stopping = 0;  // past the loop, or done: no grace
inline sem_t g_grace_wake;                         // posted by a signal and by stopping()
inline std::mutex g_grace_mutex;                   // guards the two below
inline int g_grace_users = 0;                      // StopSignals alive
inline std::thread g_grace_thread;

inline void on_stop_signal(int sig) {
  if (g_stop_signal != 0) {
    release_folder_locks_from_signal();
    ::_exit(128 + sig);
  }
  g_stop_signal = sig;
  ::sem_post(&g_grace_wake);
}

// Waits for the first signal, then for the run to stop within the grace; past it, ends the
// process as a second signal would.
inline void keep_grace() {
  while (::sem_wait(&g_grace_wake) != 0 && errno == EINTR) {
  }
  if (g_stopping) return;
  timespec deadline{};
  ::clock_gettime(CLOCK_REALTIME, &deadline);
  deadline.tv_sec += kStopGraceSeconds;
  while (true) {
    if (::sem_timedwait(&g_grace_wake, &deadline) == 0) {
      if (g_stopping) return;
      continue;  // a repeated post; the second signal itself exits in its handler
    }
    if (errno == EINTR) continue;
    break;  // ETIMEDOUT
  }
  if (g_stopping) return;
  static const char msg[] =
      "bkquake: the run reached no point to stop at within 10 s of the signal (a long event "
      "or setup); stopped at once, its last checkpoint (if any) kept, the lock released\n";
  [[maybe_unused]] const ssize_t n = ::write(2, msg, sizeof msg - 1);
  release_folder_locks_from_signal();
  ::_exit(128 + (g_stop_signal != 0 ? g_stop_signal : SIGTERM));
}
}  // namespace detail

// Has a stop been asked for? For work outside the run loop that checks in (the fit).
inline bool stop_requested() {
  return detail::g_stop_signal != 0;
}

// Installs the handlers for its lifetime and restores the previous ones after.
class StopSignals {
 public:
  StopSignals() {
    detail::g_stop_signal = 0;
    {
      const std::lock_guard<std::mutex> lock(detail::g_grace_mutex);
      if (detail::g_grace_users++ == 0) {
        detail::g_stopping = 0;
        ::sem_init(&detail::g_grace_wake, 0, 0);
        // The grace thread takes no signal: they go to the run's thread, as before.
        sigset_t all, old;
        sigfillset(&all);
        ::pthread_sigmask(SIG_BLOCK, &all, &old);
        detail::g_grace_thread = std::thread(detail::keep_grace);
        ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
      }
    }
    struct sigaction sa {};
    sa.sa_handler = detail::on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;  // a write or fsync under way completes instead of failing with EINTR
    ::sigaction(SIGINT, &sa, &old_int_);
    ::sigaction(SIGTERM, &sa, &old_term_);
    // A run started with the signals blocked (by a job launcher, or a signal sent before
    // the run could take it) still hears them: one already pending arrives now, and the
    // run stops at its first event.
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    ::pthread_sigmask(SIG_UNBLOCK, &stop, &old_mask_);
  }
  ~StopSignals() {
    ::pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
    ::sigaction(SIGINT, &old_int_, nullptr);
    ::sigaction(SIGTERM, &old_term_, nullptr);
    const std::lock_guard<std::mutex> lock(detail::g_grace_mutex);
    if (--detail::g_grace_users == 0) {
      stopping();
      detail::g_grace_thread.join();
      ::sem_destroy(&detail::g_grace_wake);
    }
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  int received() const { return detail::g_stop_signal; }
  // The run has left its loop (to stop, or to finish): from here on the first signal's
  // grace neither runs nor starts, so writing the last checkpoint is never cut short.
  void stopping() const {
    if (detail::g_stopping) return;
    detail::g_stopping = 1;
    ::sem_post(&detail::g_grace_wake);
  }

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
  sigset_t old_mask_{};
};

// What a run stopped by a signal prints: where it stopped (`progress`, e.g. "after 5 of 10
// events"), its checkpoint and the command that continues it.
inline void print_stop_notice(int sig, const std::string& progress, const std::string& checkpoint,
                              const std::string& scene_ini, const std::string& dir) {
  std::fprintf(stderr,
               "bkquake: stopped by %s %s; checkpoint in '%s'; to continue: bkquake run %s "
               "--out %s --resume\n",
               sig == SIGINT ? "SIGINT" : "SIGTERM", progress.c_str(), checkpoint.c_str(),
               scene_ini.c_str(), dir.c_str());
}

}  // namespace bkq
