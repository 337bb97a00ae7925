// The sweep's ranks over MPI (see sweep_comm.hpp): compiled only when the build finds
// Boost.MPI and MPI (CMakeLists.txt, bkquake_extra_unit), in place of sweep_comm_serial.cpp.
// Protocol: a worker sends rank 0 a request carrying its previous result (empty the first
// time) and receives the next task number, or -1 to stop: two messages per task run away
// from rank 0, none for rank 0's own. Rank 0's main thread polls for requests without
// spinning (Open MPI's blocking receive would keep a core busy that rank 0's own worker
// thread needs), sleeping 1 to 8 ms when nothing is waiting.
#include <boost/mpi.hpp>

#include <algorithm>
#include <chrono>
#include <deque>
#include <exception>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>

#include "app/sweep_comm.hpp"

namespace bkq {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

namespace mpi = boost::mpi;

constexpr int kTagRequest = 1;
constexpr int kTagTask = 2;

std::string encode(const TaskResult& r) {
  std::ostringstream s;
  s.precision(17);
  s << r.task << ' ' << r.status << ' ' << r.seconds << '\n' << r.error;
  return s.str();
}

TaskResult decode(const std::string& text) {
  TaskResult r;
  std::istringstream s(text);
  s >> r.task >> r.status >> r.seconds;
  s.get();
  std::getline(s, r.error, '\0');
  return r;
}

class MpiComm final : public SweepComm {
 public:
  MpiComm() : env_(mpi::threading::funneled) {}
  int rank() const override { return world_.rank(); }
  int size() const override { return world_.size(); }
  bool agree(bool ok) override {
    mpi::broadcast(world_, ok, 0);
    return ok;
  }

  DispatchStats dispatch(const std::vector<int>& order, const std::function<TaskResult(int)>& run,
                         const std::function<bool(const TaskResult&)>& on_result) override {
    if (world_.rank() != 0) {
      work(run);
      return {};
    }
    return serve(order, run, on_result);
  }

 private:
  // A rank other than 0: ask, run, report with the next request, until told to stop.
  void work(const std::function<TaskResult(int)>& run) {
    std::string report;
    while (true) {
      world_.send(0, kTagRequest, report);
      int task = -1;
      world_.recv(0, kTagTask, task);
      if (task < 0) return;
      report = encode(run(task));
    }
  }

  DispatchStats serve(const std::vector<int>& order, const std::function<TaskResult(int)>& run,
                      const std::function<bool(const TaskResult&)>& on_result) {
    const auto t0 = Clock::now();
    DispatchStats stats;
    std::size_t next = 0;
    bool stopping = false;
    std::mutex m;
    std::deque<TaskResult> local_results;
    bool local_done = false;
    Clock::time_point local_done_at;

    auto take = [&]() -> int {
      if (stopping || next >= order.size()) return -1;
      return order[next++];
    };
    // Rank 0's own worker: takes tasks from the same list under the lock.
    std::thread local([&] {
      while (true) {
        int task;
        {
          std::lock_guard<std::mutex> lock(m);
          task = take();
          if (task < 0) {
            local_done = true;
            local_done_at = Clock::now();
            return;
          }
        }
        TaskResult r = run(task);
        std::lock_guard<std::mutex> lock(m);
        local_results.push_back(std::move(r));
      }
    });

    int workers_left = world_.size() - 1;
    std::vector<Clock::time_point> stopped_at;
    std::string msg;
    constexpr std::chrono::microseconds kMaxSleep(8000);
    std::chrono::microseconds idle_sleep(500);
    mpi::request pending = world_.irecv(mpi::any_source, kTagRequest, msg);
    // An error in on_result (a failed write) stops the hand-out; it is thrown again once
    // every rank has stopped, so the local thread is never left running.
    std::exception_ptr failure;
    auto handle = [&](const TaskResult& r) {
      bool go_on = false;
      if (!failure) {
        try {
          go_on = on_result(r);
        } catch (...) {
          failure = std::current_exception();
        }
      }
      if (!go_on) {
        std::lock_guard<std::mutex> lock(m);
        stopping = true;
      }
    };
    while (true) {
      bool busy = false;
      std::deque<TaskResult> got;
      bool local_finished;
      {
        std::lock_guard<std::mutex> lock(m);
        got.swap(local_results);
        local_finished = local_done;
      }
      for (const auto& r : got) {
        busy = true;
        handle(r);
      }
      if (workers_left > 0) {
        if (const auto status = pending.test()) {
          busy = true;
          ++stats.messages;
          const int from = status->source();
          if (!msg.empty()) {
            ++stats.remote_tasks;
            handle(decode(msg));
          }
          int task;
          {
            std::lock_guard<std::mutex> lock(m);
            task = take();
          }
          world_.send(from, kTagTask, task);
          ++stats.messages;
          if (task < 0) {
            --workers_left;
            stopped_at.push_back(Clock::now());
          }
          msg.clear();
          if (workers_left > 0) pending = world_.irecv(mpi::any_source, kTagRequest, msg);
        }
      }
      if (workers_left == 0 && local_finished) {
        std::lock_guard<std::mutex> lock(m);
        if (local_results.empty()) break;
        continue;
      }
      // Idle: sleep 1 ms, doubling up to 8 ms while nothing comes (a request waits at most
      // that long; the wake-ups cost rank 0's core almost nothing).
      idle_sleep = busy ? std::chrono::microseconds(500) : std::min(2 * idle_sleep, kMaxSleep);
      if (!busy) std::this_thread::sleep_for(idle_sleep);
    }
    local.join();
    if (failure) std::rethrow_exception(failure);
    const auto end = Clock::now();
    for (const auto& t : stopped_at) stats.idle_at_end_seconds += seconds_between(t, end);
    stats.idle_at_end_seconds += seconds_between(local_done_at, end);
    stats.dispatch_seconds = seconds_since(t0);
    return stats;
  }

  static double seconds_between(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  }

  mpi::environment env_;
  mpi::communicator world_;
};

}  // namespace

bool mpi_available() {
  return true;
}

std::unique_ptr<SweepComm> make_sweep_comm(std::string& note) {
  if (launcher_world_size() > 0) {
    auto comm = std::make_unique<MpiComm>();
    note = "MPI, " + std::to_string(comm->size()) + (comm->size() == 1 ? " rank" : " ranks");
    return comm;
  }
  note = "one rank (not started by mpirun)";
  return make_one_rank_comm();
}

}  // namespace bkq
