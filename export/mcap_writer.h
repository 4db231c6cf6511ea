// MCAP (mcap.dev, format version 0): the container ROS 2 bags are stored in by default (rosbag2_storage_mcap). Written
// in one pass: magic, Header, then the data section as uncompressed Chunks (the schemas, channels and messages
// added since the last chunk), each followed by one Message Index per channel in it; Data End; a summary section
// (every Schema, Channel, a Statistics record and one Chunk Index per chunk, grouped by opcode) with its Summary
// Offsets; Footer; magic. Every CRC is written (the data section's from the first magic byte on, each chunk's, the
// summary's), so readers that check them (@mcap/core does by default) find any damage.
#pragma once

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace sward {

class McapWriter {
public:
    // Creates `path` and writes the magic and Header (`profile`, e.g. "ros2"; `library`: the writer's name).
    McapWriter(const std::string& path, const std::string& profile, const std::string& library);
    McapWriter(const McapWriter&) = delete;
    McapWriter& operator=(const McapWriter&) = delete;
    ~McapWriter(); // closes the file; without finish() it is incomplete

    // Returns the new schema's id (1, 2, ...).
    uint16_t addSchema(const std::string& name, const std::string& encoding, const std::string& data);
    // Returns the new channel's id (0, 1, ...).
    uint16_t addChannel(uint16_t schemaId, const std::string& topic, const std::string& messageEncoding,
                        const std::map<std::string, std::string>& metadata);
    // Appends a message to the open chunk; its sequence number counts the channel's messages from 0.
    void addMessage(uint16_t channelId, uint64_t logTime, uint64_t publishTime, const std::string& data);
    // Closes the open chunk (if it holds anything): writes it and its message indexes.
    void flushChunk();
    // Flushes, writes Data End, the summary and the Footer, and closes the file; throws on any write error.
    void finish();

private:
    struct ChunkIndex {
        uint64_t startTime, endTime, offset, length, indexLength, recordsSize;
        std::map<uint16_t, uint64_t> indexOffsets;
    };
    void write(const std::string& bytes, bool dataSection);

    std::string path_;
    std::FILE* file_ = nullptr;
    uint64_t position_ = 0;
    uint32_t dataCrc_; // running, not yet finalised
    std::vector<std::string> schemaRecords_, channelRecords_;
    std::vector<uint64_t> channelCounts_;
    std::string chunk_;                                                            // the open chunk's records
    std::map<uint16_t, std::vector<std::pair<uint64_t, uint64_t>>> chunkMessages_; // channel -> (log time, offset)
    uint64_t chunkStart_ = UINT64_MAX, chunkEnd_ = 0, startTime_ = UINT64_MAX, endTime_ = 0, messageCount_ = 0;
    std::vector<ChunkIndex> chunks_;
};

} // namespace sward
