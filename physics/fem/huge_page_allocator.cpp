#include "physics/fem/huge_page_allocator.h"

#include <sys/mman.h>

#include <cstdint>
#include <new>

namespace vesica::physics {

namespace {

std::size_t RoundUpToHugePages(std::size_t bytes) {
  return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
}

}  // namespace

std::size_t HugePageMappedBytes(std::size_t bytes) { return bytes < kHugePageMinBytes ? 0 : RoundUpToHugePages(bytes); }

void* AllocateHugePageBacked(std::size_t bytes) {
  const std::size_t length = HugePageMappedBytes(bytes);
  if (length == 0) return ::operator new (bytes, std::align_val_t{64});
  // mmap aligns to 4 KB only: map one huge page more and unmap the unaligned head and tail.
  const std::size_t padded = length + kHugePageBytes;
  void* mapped = mmap(nullptr, padded, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) throw std::bad_alloc();
  // Pointer arithmetic on the mapping itself (no integer-to-pointer casts).
  char* const base = static_cast<char*>(mapped);
  const std::size_t misalignment = reinterpret_cast<std::uintptr_t>(base) % kHugePageBytes;
  const std::size_t head = misalignment == 0 ? 0 : kHugePageBytes - misalignment;
  char* const pointer = base + head;
  if (head > 0) munmap(base, head);
  munmap(pointer + length, padded - head - length);  // never empty: head < one huge page
  // Advice only: without THP (policy "never", another kernel) the mapping keeps 4 KB pages.
  madvise(pointer, length, MADV_HUGEPAGE);
  return pointer;
}

void FreeHugePageBacked(void* pointer, std::size_t bytes) noexcept {
  if (pointer == nullptr) return;
  const std::size_t length = HugePageMappedBytes(bytes);
  if (length == 0)
    ::operator delete (pointer, std::align_val_t{64});
  else
    munmap(pointer, length);
}

}  // namespace vesica::physics
