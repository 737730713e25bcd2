// Resident-memory readings and the byte sizes of --memory-limit.

#include "strahl/core/process_memory.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

#include "strahl/core/error.h"
#include "test_support.h"

namespace strahl {
namespace {

TEST(ProcessMemory, ResidentMemoryGrowsWithTouchedPagesAndPeakFollows) {
    const size_t before = residentBytes();
    ASSERT_GT(before, 0u) << "no VmRSS in /proc/self/status";
    std::vector<char> block(64 << 20, 1);  // written, so resident
    const size_t during = residentBytes();
    EXPECT_GT(during, before + (48 << 20));
    EXPECT_GE(peakResidentBytes(), during);
    EXPECT_EQ(block[12345], 1);
}

TEST(ProcessMemory, ByteSizesUseBinaryUnits) {
    EXPECT_EQ(parseByteSize("8G", "x"), size_t(8) << 30);
    EXPECT_EQ(parseByteSize("512M", "x"), size_t(512) << 20);
    EXPECT_EQ(parseByteSize("1.5GiB", "x"), size_t(3) << 29);
    EXPECT_EQ(parseByteSize("64k", "x"), size_t(64) << 10);
    EXPECT_EQ(parseByteSize("2T", "x"), size_t(2) << 40);
    EXPECT_EQ(parseByteSize("4096", "x"), 4096u);
    EXPECT_EQ(parseByteSize("100B", "x"), 100u);
    for (const char* bad : {"", "G", "8X", "8GB2", "-1G", "0", "nan", "inf", "2000000T"})
        EXPECT_THAT(test::errorMessage([&] { parseByteSize(bad, "--memory-limit"); }),
                    testing::HasSubstr("--memory-limit: '")) << bad;
}

TEST(ProcessMemory, FormatsBytesInBinaryUnits) {
    EXPECT_EQ(formatBytes(512), "512 B");
    EXPECT_EQ(formatBytes(size_t(3) << 29), "1.50 GiB");
    EXPECT_EQ(formatBytes(size_t(310) << 20), "310.0 MiB");
}

}  // namespace
}  // namespace strahl
