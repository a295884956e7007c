#pragma once
/// \file Independent tasks run on a few threads, each worker taking the next task in order
/// (report figures, the cases of a batch). Each task writes only its own results, so what they
/// produce does not depend on the number of workers.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <system_error>
#include <thread>
#include <vector>

namespace breastfit {

/// Calls task(i) once for every i in [0, count) on up to `workers` threads (the calling one
/// included; at least one, at most one per task); a thread that cannot be started leaves its
/// tasks to the others. Returns when all are done; then rethrows the exception of the first
/// task (in task order) that threw.
inline void run_in_order(std::size_t count, unsigned workers, const std::function<void(std::size_t)>& task) {
  std::vector<std::exception_ptr> errors(count);
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t i; (i = next++) < count;) try {
        task(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
  };
  std::vector<std::thread> threads;
  const std::size_t n = std::clamp<std::size_t>(workers, 1, std::max<std::size_t>(count, 1));
  for (std::size_t w = 1; w < n; ++w) try {
      threads.emplace_back(work);
    } catch (const std::system_error&) {  // no more threads: the ones running take the rest
      break;
    }
  work();
  for (auto& t : threads) t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace breastfit
