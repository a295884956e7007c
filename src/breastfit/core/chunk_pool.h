#pragma once
/// \file The process-wide pool of worker threads behind the deterministic chunked loops (the fit
/// layer's fit/parallel_chunks.h and the spatial index build's spatial/detail/parallel_for.h).
/// A loop is a number of chunks; the calling thread runs chunks itself and up to threads − 1
/// pooled workers take the others as they come (one shared counter hands out the next chunk).
/// The caller never waits for a worker that has not started: when the workers are slow to wake
/// (another process holds the core) it runs every chunk itself and waits only for chunks already
/// taken. Idle workers spin for a short while (a few tens of microseconds: the gap between two
/// loops of a fit iteration) and then sleep on a futex (std::atomic::wait), so the pool costs no
/// CPU between fits — unlike libgomp, whose waiting policy can only be set from the environment
/// before the process starts and whose default spins for milliseconds after every loop. Which
/// thread runs a chunk never matters: callers combine the chunks' results in chunk order.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#include <sched.h>

namespace breastfit {

/// The processors this process may run on (its CPU affinity mask), at least 1.
inline int available_processors() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

namespace detail {

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

/// A value threads wait on for a change, with its own count of the threads asleep on it: a change
/// nobody sleeps through costs no system call and touches no shared waiter table.
struct WaitWord {
  std::atomic<std::uint32_t> value{0};
  std::atomic<int> sleepers{0};

  /// Spins while `value` still holds `old`, for at most `spin` of wall time, then sleeps until it
  /// changes. Returns the new value.
  std::uint32_t wait_for_change(std::uint32_t old, std::chrono::nanoseconds spin) {
    using Clock = std::chrono::steady_clock;
    const auto until = Clock::now() + spin;
    for (int k = 0;; ++k) {
      const std::uint32_t now = value.load(std::memory_order_acquire);
      if (now != old) return now;
      if ((k & 63) == 63 && Clock::now() >= until) break;
      cpu_relax();
    }
    for (;;) {
      // Announced before the last look (both sequentially consistent, as in publish()): either
      // the publisher sees a sleeper and wakes it, or this thread sees the new value.
      sleepers.fetch_add(1, std::memory_order_seq_cst);
      if (value.load(std::memory_order_seq_cst) == old) value.wait(old, std::memory_order_seq_cst);
      sleepers.fetch_sub(1, std::memory_order_relaxed);
      const std::uint32_t now = value.load(std::memory_order_acquire);
      if (now != old) return now;
    }
  }

  /// Adds `n` to the value and wakes the threads asleep on it, if any. Returns the new value.
  std::uint32_t publish(std::uint32_t n = 1) {
    const std::uint32_t now = value.fetch_add(n, std::memory_order_seq_cst) + n;
    if (sleepers.load(std::memory_order_seq_cst) > 0) value.notify_all();
    return now;
  }
};

/// True on a thread while it runs a chunk: a loop inside a chunk runs serially on that thread.
inline thread_local bool in_chunk = false;

/// One loop handed to the pool. Shared (std::shared_ptr) with the workers that look at it, so a
/// worker that wakes after the loop has ended still reads valid counters (and then finds no
/// chunk left: it never touches `fn`, which lives in the caller's frame).
struct ChunkJob {
  std::uint32_t chunks = 0;
  int max_helpers = 0;
  const std::function<void(std::size_t)>* fn = nullptr;
  alignas(64) std::atomic<std::uint32_t> next{0};  // own cache lines: taken and counted by every thread
  alignas(64) WaitWord done;                       // chunks finished
  alignas(64) std::atomic<int> helpers{0};
  std::vector<std::exception_ptr> errors;

  void work() {
    const bool outer = in_chunk;
    in_chunk = true;
    for (std::uint32_t c; (c = next.fetch_add(1, std::memory_order_relaxed)) < chunks;) {
      try {
        (*fn)(c);
      } catch (...) {
        errors[c] = std::current_exception();
      }
      done.publish();
    }
    in_chunk = outer;
  }
};

class ChunkPool {
 public:
  /// The process's pool. Never destroyed: its detached workers may still be asleep in it at exit.
  static ChunkPool& instance() {
    static ChunkPool* pool = new ChunkPool;
    return *pool;
  }

  void run(std::size_t chunks, int threads, const std::function<void(std::size_t)>& fn) {
    auto job = std::make_shared<ChunkJob>();
    job->chunks = static_cast<std::uint32_t>(chunks);
    job->fn = &fn;
    job->errors.resize(chunks);
    {
      std::lock_guard lock(mutex_);
      job->max_helpers = std::min(threads - 1, start_workers(threads - 1));
      job_ = job;
    }
    if (job->max_helpers > 0) generation_.publish();
    job->work();
    for (std::uint32_t d; (d = job->done.value.load(std::memory_order_acquire)) < job->chunks;)
      job->done.wait_for_change(d, kSpin);
    {
      std::lock_guard lock(mutex_);
      if (job_ == job) job_.reset();
    }
    for (const auto& e : job->errors)
      if (e) std::rethrow_exception(e);
  }

 private:
  // How long an idle worker (and a caller waiting for a worker's last chunk) spins before it
  // sleeps: longer than the serial work between two loops of a fit iteration, far shorter than
  // libgomp's default (300 000 pauses, milliseconds).
  static constexpr std::chrono::nanoseconds kSpin{50'000};

  ChunkPool() = default;

  // Starts workers up to `wanted` (under mutex_); returns how many there are.
  int start_workers(int wanted) {
    for (; workers_ < wanted; ++workers_) try {
        std::thread([this] { work_forever(); }).detach();
      } catch (const std::system_error&) {  // no more threads: the ones there take the chunks
        break;
      }
    return workers_;
  }

  [[noreturn]] void work_forever() {
    std::uint32_t seen = generation_.value.load(std::memory_order_acquire);
    for (;;) {
      std::shared_ptr<ChunkJob> job;
      {
        std::lock_guard lock(mutex_);
        job = job_;
      }
      if (job && job->helpers.fetch_add(1, std::memory_order_relaxed) < job->max_helpers) job->work();
      job.reset();
      seen = generation_.wait_for_change(seen, kSpin);
    }
  }

  std::mutex mutex_;
  std::shared_ptr<ChunkJob> job_;  // the loop being run (guarded by mutex_)
  int workers_ = 0;                // guarded by mutex_
  WaitWord generation_;            // counts the loops handed out
};

}  // namespace detail

/// Calls fn(c) once for every chunk c in [0, chunks): with threads <= 1 (or inside another
/// chunk) in order on the calling thread, stopping at the first exception; otherwise on the
/// calling thread and up to threads − 1 workers of the process-wide pool, in any order, and then
/// rethrows the exception of the lowest chunk that threw once every chunk has run.
inline void run_chunks(std::size_t chunks, int threads, const std::function<void(std::size_t)>& fn) {
  if (threads <= 1 || chunks <= 1 || detail::in_chunk) {
    for (std::size_t c = 0; c < chunks; ++c) fn(c);
    return;
  }
  detail::ChunkPool::instance().run(chunks, threads, fn);
}

}  // namespace breastfit
