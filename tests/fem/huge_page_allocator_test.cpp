#include "physics/fem/huge_page_allocator.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace vesica::physics {
namespace {

struct Mapping {
  bool found = false;
  std::uintptr_t begin = 0, end = 0;
  std::string flags;  // smaps' VmFlags line
};

// The /proc/self/smaps entry whose range holds `address`.
Mapping MappingOf(const void* address) {
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  Mapping m;
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream header(line);
    if (header >> std::hex >> begin >> dash >> end && dash == '-') {
      if (inside) break;
      inside = a >= begin && a < end;
      if (inside) m.found = true, m.begin = begin, m.end = end;
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      m.flags = line;
    }
  }
  return m;
}

// The process's mapped bytes (/proc/self/status VmSize).
std::size_t MappedBytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmSize:", 0) == 0) return std::stoull(line.substr(7)) * 1024;
  return 0;
}

TEST(HugePageAllocator, LargeArraysGetTheirOwnAlignedMappingAdvisedForHugePages) {
  const std::size_t bytes = 3 * kHugePageBytes + 12345;  // not a whole number of pages
  ASSERT_EQ(HugePageMappedBytes(bytes), 4 * kHugePageBytes);
  auto* p = static_cast<unsigned char*>(AllocateHugePageBacked(bytes));
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % kHugePageBytes, 0u);
  for (std::size_t i = 0; i < bytes; i += 4096) p[i] = static_cast<unsigned char>(i / 4096);
  p[bytes - 1] = 7;
  for (std::size_t i = 0; i < bytes; i += 4096) ASSERT_EQ(p[i], static_cast<unsigned char>(i / 4096));
  const Mapping m = MappingOf(p);
  ASSERT_TRUE(m.found);
  // Its own mapping, exactly the rounded length, flagged "hg" (MADV_HUGEPAGE) whatever the
  // system's THP policy.
  EXPECT_EQ(m.begin, reinterpret_cast<std::uintptr_t>(p));
  EXPECT_EQ(m.end - m.begin, 4 * kHugePageBytes);
  EXPECT_NE(m.flags.find(" hg"), std::string::npos) << m.flags;
  FreeHugePageBacked(p, bytes);
}

// The padding to the alignment is unmapped again, and freeing unmaps the rest: counted on the
// process's mapped bytes, in a forked child, which has this thread alone (in the test process
// OpenBLAS's pool threads may map a malloc arena, 128 MiB, at any moment).
TEST(HugePageAllocator, PaddingIsUnmappedAndFreeingUnmapsTheRest) {
  EXPECT_EXIT(
      {
        const std::size_t bytes = 3 * kHugePageBytes + 12345;
        MappedBytes();  // the reader's own allocations, once, before the figures
        const std::size_t before = MappedBytes();
        void* p = AllocateHugePageBacked(bytes);
        const std::size_t allocated = MappedBytes();
        FreeHugePageBacked(p, bytes);
        const std::size_t freed = MappedBytes();
        if (allocated != before + 4 * kHugePageBytes || freed != before) {
          std::fprintf(stderr, "mapped bytes %zu, then %zu with the array, %zu after freeing it\n", before, allocated,
                       freed);
          std::_Exit(1);
        }
        std::_Exit(0);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(HugePageAllocator, SmallArraysComeFromOperatorNewAligned) {
  const std::size_t bytes = kHugePageMinBytes - 8;
  EXPECT_EQ(HugePageMappedBytes(bytes), 0u);
  void* p = AllocateHugePageBacked(bytes);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % 64, 0u);
  const Mapping m = MappingOf(p);
  ASSERT_TRUE(m.found);
  EXPECT_EQ(m.flags.find(" hg"), std::string::npos) << m.flags;
  FreeHugePageBacked(p, bytes);
}

TEST(HugePageAllocator, VectorsKeepTheirValuesAcrossTheThreshold) {
  HugePageVector<double> v;
  const std::size_t n = 3 * kHugePageMinBytes / sizeof(double);
  for (std::size_t i = 0; i < n; ++i) v.push_back(0.5 * static_cast<double>(i));  // reallocates small to large
  for (std::size_t i = 0; i < n; i += 97) ASSERT_EQ(v[i], 0.5 * static_cast<double>(i));
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % kHugePageBytes, 0u);
  HugePageVector<double> copy = v;
  EXPECT_EQ(copy, v);
  v.clear();
  v.shrink_to_fit();
  EXPECT_EQ(copy[n - 1], 0.5 * static_cast<double>(n - 1));
}

}  // namespace
}  // namespace vesica::physics
