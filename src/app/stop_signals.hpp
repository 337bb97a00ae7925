// SIGINT and SIGTERM during a run (event or continuous). The first asks the run to stop
// at the next point it can (after the current event or time step: checkpoint, flush, exit
// 128 + signal); a second one exits at once, leaving the last checkpoint intact
// (checkpoints are renamed into place atomically) and removing the folder's lock. So does
// the first one when the run has not reached such a point kStopGraceSeconds later (an event
// of a wide stencil over a long chain can take minutes): every signal is honoured within
// that time, whatever loop the run is in. Once the run is stopping (stopping(): writing its
// checkpoint, which may take seconds for a long chain) nothing cuts it short but a second
// signal.
#pragma once

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <csignal>

#include "io/folder_lock.hpp"

namespace bkq {

// How long the first signal waits for the run to reach a point where it can stop.
inline constexpr unsigned kStopGraceSeconds = 10;

namespace detail {
inline volatile std::sig_atomic_t g_stop_signal = 0;
inline volatile std::sig_atomic_t g_stopping = 0;  // past the loop: no grace timer

inline void on_stop_signal(int sig) {
  if (g_stop_signal != 0) {
    release_folder_locks_from_signal();
    ::_exit(128 + sig);
  }
  g_stop_signal = sig;
  if (!g_stopping) ::alarm(kStopGraceSeconds);
}

// The grace of the first signal has passed without the run reaching a stop: as a second.
inline void on_stop_grace_over(int) {
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
    detail::g_stopping = 0;
    struct sigaction sa {};
    sa.sa_handler = detail::on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;  // a write or fsync under way completes instead of failing with EINTR
    ::sigaction(SIGINT, &sa, &old_int_);
    ::sigaction(SIGTERM, &sa, &old_term_);
    struct sigaction grace {};
    grace.sa_handler = detail::on_stop_grace_over;
    sigemptyset(&grace.sa_mask);
    ::sigaction(SIGALRM, &grace, &old_alrm_);
    // A run started with the signals blocked (by a job launcher, or a signal sent before
    // the run could take it) still hears them: one already pending arrives now, and the
    // run stops at its first event.
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    sigaddset(&stop, SIGALRM);
    ::pthread_sigmask(SIG_UNBLOCK, &stop, &old_mask_);
  }
  ~StopSignals() {
    ::alarm(0);
    ::pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
    ::sigaction(SIGINT, &old_int_, nullptr);
    ::sigaction(SIGTERM, &old_term_, nullptr);
    ::sigaction(SIGALRM, &old_alrm_, nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  int received() const { return detail::g_stop_signal; }
  // The run has left its loop (to stop, or to finish): from here on the first signal's grace
  // timer neither runs nor starts, so writing the last checkpoint is never cut short.
  void stopping() const {
    detail::g_stopping = 1;
    ::alarm(0);
  }

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
  struct sigaction old_alrm_ {};
  sigset_t old_mask_{};
};

}  // namespace bkq
