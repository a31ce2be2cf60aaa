#pragma once

#include <cstddef>
#include <vector>

namespace vesica::physics {

/// Size of a transparent huge page on x86-64 (bytes).
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

/// Arrays at least this large go to huge-page-backed mappings; smaller ones to operator new
/// (rounding a small array up to 2 MB would waste more than its TLB misses cost).
inline constexpr std::size_t kHugePageMinBytes = std::size_t{512} << 10;

/// Memory for the arrays a solver streams every iteration (the half factor, the sweeps' rows, the
/// element data): 2 MB aligned, its length rounded up to whole 2 MB pages, and advised
/// MADV_HUGEPAGE, so that the kernel backs it with transparent huge pages where its policy
/// allows ("madvise" or "always"). A step streams ~16 MB through 4 KB pages, four thousand of
/// them, more than the second-level TLB holds: every page would cost a page walk.
/// Throws std::bad_alloc when the mapping fails. Below kHugePageMinBytes, plain operator new.
void* AllocateHugePageBacked(std::size_t bytes);
/// Frees what AllocateHugePageBacked(bytes) returned (the same `bytes`).
void FreeHugePageBacked(void* pointer, std::size_t bytes) noexcept;
/// The bytes AllocateHugePageBacked(bytes) maps (0 below the threshold: those are operator new's).
std::size_t HugePageMappedBytes(std::size_t bytes);

/// A std::allocator for vectors of the streamed arrays (HugePageVector).
template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  explicit HugePageAllocator(const HugePageAllocator<U>& /*other*/) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(AllocateHugePageBacked(n * sizeof(T))); }
  void deallocate(T* pointer, std::size_t n) noexcept { FreeHugePageBacked(pointer, n * sizeof(T)); }
  friend bool operator==(const HugePageAllocator& /*a*/, const HugePageAllocator& /*b*/) { return true; }
};

template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace vesica::physics
