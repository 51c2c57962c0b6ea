#pragma once
// A loop over independent chunks (each chunk's results its own, written by it alone) for a host
// whose threads do not run at one speed. Each thread starts on its own contiguous share of the
// chunks, in order, as a static schedule would; a thread that finishes its share takes the chunks
// left at the far end of another thread's share. A thread that the host slows for a while (another
// guest on its core, an interrupt) then hands its last chunks to the others instead of holding up
// the end of the region, while most chunks stay on the thread that ran them in the previous step
// (its cache). Which thread runs a chunk changes no result: the same bits for any thread count
// and any timing (docs/performance-coupled-step.md, "Chunks taken from a slower thread").
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace erythro::parallel {

// Shares on the stack of the call (no allocation per loop): more threads than this share the
// chunks as this many shares, taken in turn.
constexpr int kMaxShares = 64;

namespace detail {

// The chunks [front, back) left in one share, in one word: its owner takes the front, another
// thread the back, and one compare-and-swap decides who gets the last chunk.
struct alignas(64) Share {
  std::atomic<std::uint64_t> ends{0};
};

inline std::uint64_t pack(std::uint32_t front, std::uint32_t back) {
  return (std::uint64_t{back} << 32) | std::uint64_t{front};
}

// The front (from_front) or the back chunk of s into `chunk`; false once s is empty. Every chunk
// is taken exactly once: the word's updates are totally ordered.
inline bool take(Share& s, bool from_front, long& chunk) {
  std::uint64_t word = s.ends.load(std::memory_order_relaxed);
  for (;;) {
    const std::uint32_t front = static_cast<std::uint32_t>(word), back = static_cast<std::uint32_t>(word >> 32);
    if (front >= back) return false;
    const std::uint64_t rest = from_front ? pack(front + 1, back) : pack(front, back - 1);
    if (s.ends.compare_exchange_weak(word, rest, std::memory_order_relaxed)) {
      chunk = from_front ? long{front} : long{back} - 1;
      return true;
    }
  }
}

}  // namespace detail

// body(c) for every c in [0, chunks), each exactly once, on up to `threads` threads; body must
// not throw (an exception cannot leave an OpenMP region). On one thread, inside another parallel
// region (whose nested region would have a team of one) or without OpenMP: in ascending order
// on the caller's thread.
template <class Body>
void for_each_chunk(long chunks, int threads, Body&& body) {
#if defined(_OPENMP)
  const int shares = static_cast<int>(std::min<long>({threads, chunks, kMaxShares}));
  if (shares > 1 && chunks <= std::numeric_limits<std::uint32_t>::max() && !omp_in_parallel()) {
    detail::Share share[kMaxShares];
    for (int s = 0; s < shares; ++s) {
      const long first = chunks * s / shares, last = chunks * (s + 1) / shares;
      share[s].ends.store(detail::pack(static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(last)),
                          std::memory_order_relaxed);
    }
#pragma omp parallel num_threads(shares)
    {
      // Its own share from the front, then the others' from the back, the next thread's first.
      // A team smaller than asked for leaves shares without an owner: the others empty them.
      const int t = omp_get_thread_num();
      long c;
      for (int k = 0; k < shares; ++k) {
        const int s = (t + k) % shares;
        while (detail::take(share[s], k == 0, c)) body(c);
      }
    }
    return;
  }
#else
  (void)threads;
#endif
  for (long c = 0; c < chunks; ++c) body(c);
}

// body(first, last) for the consecutive ranges [first, last) of `per_chunk` items (the last one
// shorter) that cover [0, items), each range one chunk of for_each_chunk.
template <class Body>
void for_each_range(long items, long per_chunk, int threads, Body&& body) {
  for_each_chunk((items + per_chunk - 1) / per_chunk, threads, [&](long c) {
    const long first = c * per_chunk;
    body(first, std::min(items, first + per_chunk));
  });
}

}  // namespace erythro::parallel
