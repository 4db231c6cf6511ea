// The one strict parser of command-line numbers: digits only, overflow refused, ranges enforced, no wrap.
#include "common/error.h"
#include "common/parse_number.h"
#include "test_files.h"

#include <gtest/gtest.h>

#include <functional>

using namespace sward;
using sward::test::errorOf;

TEST(ParseNumber, UnsignedAcceptsDigitsWithinRange) {
    EXPECT_EQ(parseUnsigned("0", 0, 10, "--n"), 0u);
    EXPECT_EQ(parseUnsigned("0010", 0, 10, "--n"), 10u);
    EXPECT_EQ(parseUnsigned("18446744073709551615", 0, UINT64_MAX, "--n"), UINT64_MAX);
}

TEST(ParseNumber, UnsignedRefusesWhatSscanfWouldWrapOrAccept) {
    for (const char* bad : {"", "-1", "+1", " 1", "1 ", "0x10", "1e3", "1.0", "4294967296", "4294967616",
                            "18446744073709551616", "99999999999999999999999", "11"})
        EXPECT_THROW(parseUnsigned(bad, 0, 10, "--n"), Error) << bad;
    EXPECT_EQ(errorOf([] { parseUnsigned("4294967296", 1, 4, "--samples"); }),
              "--samples must be a whole number from 1 to 4, got '4294967296'");
}

TEST(ParseNumber, IntegerTakesOneLeadingMinus) {
    EXPECT_EQ(parseInteger("-5", -10, 10, "--d"), -5);
    EXPECT_EQ(parseInteger("-9223372036854775808", INT64_MIN, INT64_MAX, "--d"), INT64_MIN);
    for (const char* bad : {"", "-", "--5", "+5", "5-", "-11", "11", "9223372036854775808"})
        EXPECT_THROW(parseInteger(bad, -10, 10, "--d"), Error) << bad;
}

TEST(ParseNumber, RealIsFiniteAndInRange) {
    EXPECT_EQ(parseReal("1.5", 0.0, 2.0, "--x"), 1.5);
    EXPECT_EQ(parseReal("-2e-1", -1.0, 1.0, "--x"), -0.2);
    for (const char* bad : {"", "nan", "inf", "-inf", "1e999", "0x1p3", "+1", " 1", "1,5", "3", "1.5x"})
        EXPECT_THROW(parseReal(bad, 0.0, 2.0, "--x"), Error) << bad;
    EXPECT_EQ(errorOf([] { parseReal("nan", 1.0, 170.0, "--fov"); }),
              "--fov must be a number from 1 to 170, got 'nan'");
}

TEST(ParseNumber, SplitPairNeedsExactlyOneSeparator) {
    const auto [a, b] = splitPair("3/4", '/', "shard", "I/N");
    EXPECT_EQ(a, "3");
    EXPECT_EQ(b, "4");
    EXPECT_THROW(splitPair("3", '/', "shard", "I/N"), Error);
    EXPECT_THROW(splitPair("1/2/3", '/', "shard", "I/N"), Error);
}

TEST(ParseNumber, HalfOpenRangeRefusesEmptyReversedAndHugeRanges) {
    EXPECT_EQ(parseHalfOpenRange("0:60", 0, kFrameLimit, "--frames"), std::make_pair(uint64_t(0), uint64_t(60)));
    EXPECT_EQ(parseHalfOpenRange("999999:1000000", 0, kFrameLimit, "--frames").second, uint64_t(kFrameLimit));
    for (const char* bad : {"5:5", "6:5", "0:1000001", "4294967296:4294967297", "1:", ":2", "1-2", "1:2:3", "-1:2"})
        EXPECT_THROW(parseHalfOpenRange(bad, 0, kFrameLimit, "--frames"), Error) << bad;
}
