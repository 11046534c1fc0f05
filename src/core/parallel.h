// Rows of an image on several threads, deterministically: what the CPU reference and the CPU
// shading integrals share.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "core/progress.h"

namespace penumbra {

// Runs body(y, count) for every row y on `threads` threads (0: every core). Rows are taken from
// a shared counter; each pixel's result must depend only on the pixel, so the output does not
// depend on the thread count or schedule. Returns the sum of what the bodies added to their
// `count` (rays cast, for instance). Rethrows the first exception of any thread. `progress`, if
// given, advances by one per row (a long pass says how far it is).
template <class Body>
std::uint64_t parallelRows(int height, unsigned threads, Body body, PassProgress* progress = nullptr) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  std::atomic<int> next{0};
  std::atomic<std::uint64_t> total{0};
  std::exception_ptr error;
  std::mutex errorMutex;
  auto worker = [&] {
    std::uint64_t local = 0;
    try {
      for (int y = next++; y < height; y = next++) {
        body(y, local);
        if (progress) progress->advance();
      }
    } catch (...) {
      std::lock_guard lock(errorMutex);
      if (!error) error = std::current_exception();
      next = height;
    }
    total += local;
  };
  threads = std::min<unsigned>(threads, unsigned(std::max(1, height)));
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < threads; ++i) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  return total;
}

}  // namespace penumbra
