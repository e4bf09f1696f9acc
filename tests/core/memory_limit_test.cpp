// core/memory_limit.h: sizes parse and print, the machine's memory is read, and a passed limit is one
// InputError naming the parameter, the need and the limit.
#include "core/memory_limit.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace cpgi {
namespace {

TEST(MemoryLimit, SizesParseWithUnits) {
  EXPECT_EQ(parseByteSize("8G"), uint64_t(8) << 30);
  EXPECT_EQ(parseByteSize("512M"), uint64_t(512) << 20);
  EXPECT_EQ(parseByteSize("1.5GiB"), uint64_t(3) << 29);
  EXPECT_EQ(parseByteSize("100000"), 100000u);
  for (const char* bad : {"", "G", "8Q", "-1G", "nan", "inf", "0", "1e30T"})
    EXPECT_EQ(parseByteSize(bad), 0u) << bad;
  EXPECT_EQ(formatBytes(3.0 * (1 << 30)), "3 GiB");
  EXPECT_EQ(formatBytes(100), "100 bytes");
}

TEST(MemoryLimit, DefaultIsAShareOfTheMachine) {
  const uint64_t total = physicalMemory();
  ASSERT_GT(total, uint64_t(64) << 20);  // Linux always has /proc/meminfo
  EXPECT_EQ(defaultMemoryLimit(), total / 4 * 3);
}

TEST(MemoryLimit, PassingTheLimitNamesNeedAndLimit) {
  EXPECT_NO_THROW(requireMemory(1e9, uint64_t(2) << 30, "x", "y", "z"));
  EXPECT_NO_THROW(requireMemory(1e18, 0, "x", "y", "z"));  // no limit
  try {
    requireMemory(3.0 * (1 << 30), uint64_t(1) << 30, "texels per quad", "the lightmap atlas of 8x8 texels",
                  "lower the resolution");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "texels per quad");
    EXPECT_EQ(
        e.problem(),
        "the lightmap atlas of 8x8 texels needs about 3 GiB, more than `maximum memory` 1 GiB; lower the "
        "resolution");
  }
}

}  // namespace
}  // namespace cpgi
