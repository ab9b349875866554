#pragma once
// Latest-value exchange for one writer and any number of readers that never block
// the writer (the driver thread) and never block themselves (the render thread).
// The data lives in atomic words, so the protocol is race-free in the C++ memory
// model (and under ThreadSanitizer), not only in practice.
#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace foveal {

template <class T>
class SeqLock {
  static_assert(std::is_trivially_copyable_v<T>, "SeqLock holds plain data");
  static constexpr std::size_t kWords = (sizeof(T) + 7) / 8;
  // Lock-free atomics are also address-free: the block may live in shared memory.
  static_assert(std::atomic<std::uint32_t>::is_always_lock_free && std::atomic<std::uint64_t>::is_always_lock_free);

 public:
  SeqLock() { store(T{}); }

  /// Publishes `v`. One writer at a time. Wait-free.
  void store(const T& v) {
    std::array<std::uint64_t, kWords> w{};
    std::memcpy(w.data(), &v, sizeof(T));
    const std::uint32_t s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);  // odd: a write is in progress
    // Release stores keep the odd sequence number ahead of the data (no fences: they
    // cost nothing on x86 and ThreadSanitizer understands them).
    for (std::size_t i = 0; i < kWords; ++i) words_[i].store(w[i], std::memory_order_release);
    seq_.store(s + 2, std::memory_order_release);
  }

  /// Copies the latest complete value into `out`; false only if a write overlapped
  /// every one of `tries` attempts (the writer runs at ~120 Hz: practically never).
  bool load(T& out, int tries = 64) const {
    for (int t = 0; t < tries; ++t) {
      const std::uint32_t s1 = seq_.load(std::memory_order_acquire);
      if (s1 & 1u) continue;
      std::array<std::uint64_t, kWords> w;
      // Acquire loads keep the sequence re-check behind the data.
      for (std::size_t i = 0; i < kWords; ++i) w[i] = words_[i].load(std::memory_order_acquire);
      if (seq_.load(std::memory_order_relaxed) == s1) {
        std::memcpy(static_cast<void*>(&out), w.data(), sizeof(T));  // T is trivially copyable
        return true;
      }
    }
    return false;
  }

  /// Number of completed writes.
  std::uint32_t version() const { return seq_.load(std::memory_order_acquire) / 2; }

 private:
  std::atomic<std::uint32_t> seq_{0};
  std::array<std::atomic<std::uint64_t>, kWords> words_{};
};

}  // namespace foveal
