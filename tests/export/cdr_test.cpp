// CdrWriter: XCDR1 little-endian as rclcpp writes it, byte by byte.
#include "export/cdr.h"

#include <gtest/gtest.h>

using sward::CdrWriter;

TEST(Cdr, AlignsEachPrimitiveToItsSizeCountedAfterTheEncapsulationHeader) {
    CdrWriter cdr;
    cdr.put(uint8_t(7)).put(double(1.0)).put(uint16_t(0x0102));
    // header 00 01 00 00 | 07 | 7 bytes padding to offset 8 | 1.0 | 02 01
    const std::string expected("\0\1\0\0\7\0\0\0\0\0\0\0\0\0\0\0\0\0\xf0\x3f\2\1", 22);
    EXPECT_EQ(cdr.bytes(), expected);
}

TEST(Cdr, StringsCarryTheirTerminatorInTheLengthAndSequencesTheirCount) {
    CdrWriter cdr;
    cdr.string("ab").byteSequence("xyz").put(uint32_t(5));
    // "ab": length 3, 'a' 'b' NUL; uint8[]: count 3 at offset 7 -> padded to 8; uint32 at 15 -> padded to 16.
    const std::string expected("\0\1\0\0"
                               "\3\0\0\0ab\0"
                               "\0"
                               "\3\0\0\0xyz"
                               "\0"
                               "\5\0\0\0",
                               4 + 7 + 1 + 7 + 1 + 4);
    EXPECT_EQ(cdr.bytes(), expected);
}
