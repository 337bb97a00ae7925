// SIGINT and SIGTERM during a run (event or continuous). The first asks the run to stop
// at the next point it can (after the current event or time step: checkpoint, flush, exit
// 128 + signal); a second one exits at once, leaving the last checkpoint intact
// (checkpoints are renamed into place atomically) and removing the folder's lock.
#pragma once

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <csignal>

#include "io/folder_lock.hpp"

namespace bkq {

namespace detail {
inline volatile std::sig_atomic_t g_stop_signal = 0;

inline void on_stop_signal(int sig) {
  if (g_stop_signal != 0) {
    release_folder_locks_from_signal();
    ::_exit(128 + sig);
  }
  g_stop_signal = sig;
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
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  int received() const { return detail::g_stop_signal; }

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
  sigset_t old_mask_{};
};

}  // namespace bkq
