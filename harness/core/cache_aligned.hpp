#pragma once
// An allocator whose blocks start on a cache-line (64-byte) boundary. Kernels that carve their
// small working arrays out of one such block get the same alignment and relative placement on
// every run, so their timing does not depend on where the heap happened to put each array
// (a 16-byte-aligned block can straddle cache lines differently from run to run).
#include <cstddef>
#include <new>
#include <vector>

namespace dabench {

template <class T>
struct CacheAlignedAllocator {
  using value_type = T;
  static constexpr std::size_t kAlignment = 64;

  CacheAlignedAllocator() = default;
  template <class U>
  CacheAlignedAllocator(const CacheAlignedAllocator<U>&) noexcept {}

  T* allocate(std::size_t count) {
    return static_cast<T*>(::operator new(count * sizeof(T), std::align_val_t{kAlignment}));
  }
  void deallocate(T* pointer, std::size_t) noexcept { ::operator delete(pointer, std::align_val_t{kAlignment}); }
  template <class U>
  bool operator==(const CacheAlignedAllocator<U>&) const noexcept {
    return true;
  }
};

template <class T>
using CacheAlignedVector = std::vector<T, CacheAlignedAllocator<T>>;

}  // namespace dabench
