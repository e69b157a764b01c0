/// \file gmp_block_cache.cpp
/// GMP's limb arrays reused through a small per-thread cache, in the sanitizer build only (linked into
/// the CLI and the test programs of the asan preset, not its fuzzers: tests/sanitizers/CMakeLists.txt;
/// never into a release build).
///
/// Why: the exact arithmetic (Boost's `mpq_rational`, MPFR, MPFI) allocates and frees a limb array
/// at nearly every operation, and AddressSanitizer's allocator (redzones, the call stack of every
/// allocation, the quarantine) made most of the sanitizer stage's time: `perf` of its slowest test
/// found two thirds of it in `__asan::Allocator` and its quarantine. Those arrays are read and written
/// by GMP and MPFR alone, which are not instrumented: ASan checks no access to them, so its redzones
/// and quarantine bought nothing there. Every other allocation (the project's own containers, strings,
/// matrices of exact numbers) still goes through ASan's allocator, checked as before.
///
/// What still holds for the limb arrays: each block comes from `malloc` (ASan's), so one that the
/// program loses (a number never destroyed) is unreachable at exit and LeakSanitizer reports it; the
/// cached blocks are reachable from the cache while cached and go back to `free` when their thread
/// ends. A block is kept only under a cap per size (no unbounded growth), larger ones go straight to
/// `free`.
#include <gmp.h>
#include <malloc.h>

#include <array>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

constexpr std::size_t kGrain = 16;       // size classes of 16 bytes (two limbs) ...
constexpr std::size_t kClasses = 32;     // ... up to 512 bytes (64 limbs); larger blocks are not cached
constexpr std::size_t kPerClass = 1024;  // at most this many blocks of a class wait in a thread's cache

struct Node {
  Node* next;
};

/// One thread's free lists. A block on a list is still allocated as far as ASan knows (it was never
/// given back to `free`), so writing its link into it is an ordinary access to live memory.
class Cache {
 public:
  Cache() = default;
  Cache(const Cache&) = delete;
  Cache& operator=(const Cache&) = delete;
  ~Cache() {
    for (Node*& head : heads_)
      while (head) {
        Node* next = head->next;
        std::free(head);
        head = next;
      }
    dead_ = true;  // a number destroyed after this (a thread_local or static one) is freed directly
  }
  static bool dead() { return dead_; }
  void* take(std::size_t cls) {
    Node* n = heads_[cls];
    if (!n) return nullptr;
    heads_[cls] = n->next;
    --counts_[cls];
    return n;
  }
  bool keep(void* p, std::size_t cls) {
    if (counts_[cls] >= kPerClass) return false;
    Node* n = static_cast<Node*>(p);
    n->next = heads_[cls];
    heads_[cls] = n;
    ++counts_[cls];
    return true;
  }

 private:
  std::array<Node*, kClasses> heads_{};
  std::array<std::size_t, kClasses> counts_{};
  static thread_local bool dead_;
};
thread_local bool Cache::dead_ = false;

Cache* cache() {
  if (Cache::dead()) return nullptr;
  thread_local Cache c;
  return &c;
}

/// The class of a request of n bytes (the block is allocated at the class's full size, so a block of
/// a class serves any request of it), or kClasses when it is not cached.
std::size_t class_of(std::size_t n) { return n == 0 ? 0 : (n - 1) / kGrain; }

void* allocate(std::size_t n) {
  const std::size_t cls = class_of(n);
  if (cls < kClasses) {
    if (Cache* c = cache())
      if (void* p = c->take(cls)) return p;
    n = (cls + 1) * kGrain;
  }
  void* p = std::malloc(n);
  if (!p) {  // as GMP's own allocator does: no exception may cross GMP's C frames
    std::fputs("GMP: cannot allocate memory\n", stderr);
    std::abort();
  }
  return p;
}

void release(void* p, std::size_t) {
  if (!p) return;
  // The block's own size, not the one GMP passes (it need not be the size asked for, and a block
  // allocated before this file's functions were installed has no class of ours).
  const std::size_t size = malloc_usable_size(p);
  if (size % kGrain == 0) {
    const std::size_t cls = class_of(size);
    if (cls < kClasses)
      if (Cache* c = cache())
        if (c->keep(p, cls)) return;
  }
  std::free(p);
}

void* reallocate(void* p, std::size_t old_size, std::size_t n) {
  if (!p) return allocate(n);
  const std::size_t have = malloc_usable_size(p);
  if (n <= have && class_of(n) == class_of(have)) return p;  // the block already serves n bytes
  void* q = allocate(n);
  std::memcpy(q, p, have < n ? have : n);
  release(p, old_size);
  return q;
}

/// Installed before any other static initialiser of the program runs (the exact constants of some
/// files are numbers), so that every block GMP frees later was allocated by `malloc`.
__attribute__((constructor(101))) void install() { mp_set_memory_functions(allocate, reallocate, release); }

}  // namespace
