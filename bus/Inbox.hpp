// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <atomic>
#include <mutex>
#include <utility>
#include <vector>

namespace flatsat::bus {

/// What other threads hand a component's step thread (operator commands and
/// their acknowledgements): pushed from any thread, taken whole at a step.
/// The step looks every step and finds it empty nearly always; that look
/// takes no lock (the lock pairs of those empty looks were about a thousand
/// instructions a composed step, callgrind).
template <class T>
class Inbox {
 public:
  void push(T item) {
    std::lock_guard lock(mutex_);
    items_.push_back(std::move(item));
    any_.store(true, std::memory_order_release);
  }
  /// Everything pushed so far, oldest first; empty without allocating.
  std::vector<T> takeAll() {
    std::vector<T> taken;
    if (!any_.load(std::memory_order_acquire)) return taken;
    std::lock_guard lock(mutex_);
    taken.swap(items_);
    any_.store(false, std::memory_order_relaxed);
    return taken;
  }

 private:
  std::mutex mutex_;
  std::vector<T> items_;
  std::atomic<bool> any_{false};  // items_ is not empty; set under mutex_
};

}  // namespace flatsat::bus
