// cli/huge_pages.cpp: the qmotion executable's global operator new, over malloc, asking
// for transparent huge pages (madvise(MADV_HUGEPAGE); Debian's default THP mode is
// "madvise", so nothing else gets them) for blocks of 2 MiB and more (a 10^4-pose file's
// text, its parser's index, the control points) and for each growth of malloc's heap (the
// many small blocks of the interpolation and the trees). First-touch page faults were a
// quarter of `eval`, `info` and `interpolate` on a 10^4-pose motion, and on a virtual
// machine each costs microseconds; 2 MiB pages need 512 times fewer. Measured in one run
// (best of 5): eval 0.19 -> 0.12 s, info 0.29 -> 0.20 s, interpolate 0.26 -> 0.18 s, peak
// RSS within 3 MB. The library is untouched: a program of its own gets the same from glibc
// with GLIBC_TUNABLES=glibc.malloc.hugetlb=1. Sanitized builds keep their own operator new.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)  // GCC
#define QMOTION_SANITIZED 1
#elif defined(__has_feature)  // Clang
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
#define QMOTION_SANITIZED 1
#endif
#endif
#ifndef QMOTION_SANITIZED
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>

namespace {
constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;

/// Asks for huge pages on [first, last) rounded inward to whole huge pages.
void advise(std::uintptr_t first, std::uintptr_t last) {
  first = (first + kHugePage - 1) & ~(kHugePage - 1);
  last &= ~(kHugePage - 1);
  if (last > first)  // advice only: a kernel without THP refuses it, and nothing changes
    (void)madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
}

/// The heap's end when last advised. glibc grows its main heap by brk; sbrk(0) reads its
/// cached end without a system call, so a growth is seen at the next allocation and the new
/// part advised (what glibc.malloc.hugetlb=1 does inside malloc).
std::atomic<std::uintptr_t> advised_end{0};

void advise_heap_growth() {
  // The heap grows 16 MiB beyond each need and gives back only what lies above that, so its
  // growths hold whole huge pages. A growth's two partial huge pages at its ends stay small
  // pages: with 4 MiB growths that was every other huge page of the heap. Measured
  // in one run (best of 7, 10^4 poses), growths of 4 -> 16 MiB: info 0.165 -> 0.138 s,
  // interpolate 0.166 -> 0.140 s, eval 0.122 -> 0.105 s, trajectory -> JSON 0.198 ->
  // 0.183 s, sweep -> JSON 0.319 -> 0.275 s; peak RSS -2 to +4 MB (8 MiB: half the gain;
  // 32 MiB: no more). Blocks up to 32 MiB (a vector doubling, a file's text)
  // come from that heap too, and its freed space is reused: by default glibc maps each
  // block above 128 KiB on its own and unmaps it when freed, so every such block is
  // touched page by page afresh. One arena: the writer's worker threads share the
  // advised heap instead of heaps of their own. Measured in one run (best of 9, 10^4
  // poses): trajectory -> JSON 0.270 -> 0.216 s, sweep -> JSON 0.384 -> 0.304 s,
  // interpolate 0.178 -> 0.157 s; peak RSS 3-9 MB higher (a block freed in the heap is
  // kept for reuse, and a huge page counts whole once touched). A threshold of 2, 4 or
  // 8 MiB saves 1-4 MB of that but gives back most of the time: the big blocks reused
  // are the motion file's text and its parser's buffers.
  static const bool tuned = mallopt(M_TOP_PAD, 16 << 20) && mallopt(M_TRIM_THRESHOLD, 8 << 20) &&
                            mallopt(M_MMAP_THRESHOLD, 32 << 20) && mallopt(M_ARENA_MAX, 1);
  (void)tuned;
  const auto end = reinterpret_cast<std::uintptr_t>(sbrk(0));
  std::uintptr_t before = advised_end.load(std::memory_order_relaxed);
  if (end == before || !advised_end.compare_exchange_strong(before, end)) return;
  if (before != 0 && end > before) advise(before, end);
}
}  // namespace

// Every block comes from malloc, so every delete is free (the standard's default delete
// forms forward here).
void* operator new(std::size_t n) {
  void* p = std::malloc(n ? n : 1);
  if (!p) throw std::bad_alloc();
  if (n >= kHugePage)
    advise(reinterpret_cast<std::uintptr_t>(p), reinterpret_cast<std::uintptr_t>(p) + n);
  advise_heap_growth();
  return p;
}

void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#endif
