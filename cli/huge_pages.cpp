// cli/huge_pages.cpp: the qmotion executable's global operator new, over malloc, asking
// for transparent huge pages (madvise(MADV_HUGEPAGE); Debian's default THP mode is
// "madvise", so nothing else gets them) for blocks of 2 MiB and more (a 10^4-pose file's
// text, the control points), and setting glibc's tuning (tune_malloc). First-touch page
// faults were a quarter of `eval`, `info` and `interpolate` on a 10^4-pose motion, and on a
// virtual machine each costs microseconds; 2 MiB pages need 512 times fewer. The library is
// untouched: a program of its own tunes glibc as it likes. Sanitized builds keep their own
// operator new.
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

/// glibc's tuning, set once. Blocks up to 32 MiB (a vector doubling, a file's text) come from
/// the main heap, and its freed space is reused: by default glibc maps each block above
/// 128 KiB on its own and unmaps it when freed, so every such block is touched page by page
/// afresh. One arena: the writer's worker threads share the heap instead of heaps of their
/// own. The heap grows 16 MiB beyond each need and keeps 8 MiB of free top.
///
/// The heap's growths are not advised for huge pages (they were until issue 56): a huge
/// page counts whole in the peak RSS once touched, and whether the kernel has one free at
/// each fault varies from run to run, so the peak of one command on one file varied by
/// 2 MB (trajectory -> JSON at 10^4 poses: 31.2 to 33.8 MB over 7 runs, against a target
/// of 3 x its 11 MB file), which is what made bench.memory_target fail now and then.
/// Without that advice the same command varies by 0.2 MB; the time it saved was 3-6 %
/// (info 0.102 -> 0.108 s, sweep -> JSON 0.225 -> 0.231 s, best of 7).
void tune_malloc() {
  static const bool tuned = mallopt(M_TOP_PAD, 16 << 20) && mallopt(M_TRIM_THRESHOLD, 8 << 20) &&
                            mallopt(M_MMAP_THRESHOLD, 32 << 20) && mallopt(M_ARENA_MAX, 1);
  (void)tuned;
}
}  // namespace

// Every block comes from malloc, so every delete is free (the standard's default delete
// forms forward here).
void* operator new(std::size_t n) {
  void* p = std::malloc(n ? n : 1);
  if (!p) throw std::bad_alloc();
  if (n >= kHugePage)
    advise(reinterpret_cast<std::uintptr_t>(p), reinterpret_cast<std::uintptr_t>(p) + n);
  tune_malloc();
  return p;
}

void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#endif
