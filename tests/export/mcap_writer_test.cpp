// McapWriter: the file's frame as the MCAP specification lays it out (magic, Header, Chunk, Message Index, Data End,
// summary, Footer, magic), read back with offsets of this test's own; the full decode is the Node.js readers'
// (tests/tools/sward-export/ros2_bag_test.cpp).
#include "export/mcap_writer.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace {

template <typename T> T at(const std::string& bytes, size_t offset) {
    T value;
    std::memcpy(&value, bytes.data() + offset, sizeof(T));
    return value;
}

} // namespace

TEST(McapWriter, WritesMagicHeaderChunkSummaryAndAFooterThatFindsTheSummary) {
    const std::string path =
        (std::filesystem::temp_directory_path() / ("sward-mcap-" + std::to_string(::getpid()) + ".mcap")).string();
    {
        sward::McapWriter mcap(path, "ros2", "test");
        const uint16_t schema = mcap.addSchema("pkg/msg/T", "ros2msg", "int32 a\n");
        const uint16_t channel = mcap.addChannel(schema, "/t", "cdr", {{"offered_qos_profiles", ""}});
        EXPECT_EQ(schema, 1);
        EXPECT_EQ(channel, 0);
        mcap.addMessage(channel, 5, 5, std::string("\0\1\0\0\x2a\0\0\0", 8));
        mcap.finish();
    }
    std::ifstream file(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    std::filesystem::remove(path);
    const std::string magic("\x89MCAP0\r\n", 8);
    ASSERT_GT(bytes.size(), 100u);
    EXPECT_EQ(bytes.substr(0, 8), magic);
    EXPECT_EQ(bytes.substr(bytes.size() - 8), magic);
    EXPECT_EQ(bytes[8], 0x01); // Header
    // "ros2" then "test", each a uint32 length and the bytes
    EXPECT_EQ(at<uint64_t>(bytes, 9), 4u + 4 + 4 + 4);
    EXPECT_EQ(bytes.substr(21, 4), "ros2");
    const size_t chunk = 9 + 8 + 16;
    EXPECT_EQ(bytes[chunk], 0x06);
    EXPECT_EQ(at<uint64_t>(bytes, chunk + 9), 5u);  // message_start_time
    EXPECT_EQ(at<uint64_t>(bytes, chunk + 17), 5u); // message_end_time
    // Footer: opcode, length 20, summary_start, summary_offset_start, summary_crc; then the magic.
    const size_t footer = bytes.size() - 8 - 29;
    EXPECT_EQ(bytes[footer], 0x02);
    EXPECT_EQ(at<uint64_t>(bytes, footer + 1), 20u);
    const uint64_t summary = at<uint64_t>(bytes, footer + 9), offsets = at<uint64_t>(bytes, footer + 17);
    ASSERT_LT(summary, offsets);
    EXPECT_EQ(bytes[summary], 0x03);      // the summary starts with the Schema group
    EXPECT_EQ(bytes[summary - 13], 0x0F); // after Data End (opcode, length 4, CRC)
    EXPECT_EQ(bytes[offsets], 0x0E);      // Summary Offset records
    EXPECT_NE(at<uint32_t>(bytes, footer + 25), 0u);
}
