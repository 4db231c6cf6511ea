#include "export/mcap_writer.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/little_endian.h"

#include <array>
#include <cerrno>

namespace sward {

namespace {

constexpr char kMagic[] = "\x89MCAP0\r\n";
enum Opcode : uint8_t {
    kHeader = 0x01,
    kFooter = 0x02,
    kSchema = 0x03,
    kChannel = 0x04,
    kMessage = 0x05,
    kChunk = 0x06,
    kMessageIndex = 0x07,
    kChunkIndex = 0x08,
    kStatistics = 0x0B,
    kSummaryOffset = 0x0E,
    kDataEnd = 0x0F,
};

// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320), MCAP's checksum, as zlib's crc32 computes it.
constexpr std::array<uint32_t, 256> kCrcTable = [] {
    std::array<uint32_t, 256> table{};
    for (uint32_t n = 0; n < 256; ++n) {
        uint32_t c = n;
        for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[n] = c;
    }
    return table;
}();
// `crc` is the running value: start from 0xFFFFFFFF, finish with ~crc.
uint32_t crcUpdate(uint32_t crc, const std::string& bytes) {
    for (const char c : bytes) crc = kCrcTable[(crc ^ uint8_t(c)) & 0xFF] ^ (crc >> 8);
    return crc;
}
uint32_t crc32(const std::string& bytes) {
    return ~crcUpdate(0xFFFFFFFFu, bytes);
}

void putString(std::string& out, const std::string& text) {
    appendLittleEndian(out, uint32_t(text.size()));
    out += text;
}

std::string record(Opcode opcode, const std::string& content) {
    std::string bytes(1, char(opcode));
    appendLittleEndian(bytes, uint64_t(content.size()));
    return bytes + content;
}

std::string messageIndexRecord(uint16_t channel, const std::vector<std::pair<uint64_t, uint64_t>>& entries) {
    std::string content;
    appendLittleEndian(content, channel, uint32_t(entries.size() * 16));
    for (const auto& [time, offset] : entries) appendLittleEndian(content, time, offset);
    return record(kMessageIndex, content);
}

} // namespace

McapWriter::McapWriter(const std::string& path, const std::string& profile, const std::string& library)
    : path_(path), dataCrc_(0xFFFFFFFFu) {
    file_ = std::fopen(path.c_str(), "wb");
    if (!file_) throw Error("cannot create '" + path + "': " + ioErrorReason(errno));
    std::string header;
    putString(header, profile);
    putString(header, library);
    write(std::string(kMagic, 8) + record(kHeader, header), true);
}

McapWriter::~McapWriter() {
    if (file_) std::fclose(file_);
}

uint16_t McapWriter::addSchema(const std::string& name, const std::string& encoding, const std::string& data) {
    const uint16_t id = uint16_t(schemaRecords_.size() + 1);
    std::string content;
    appendLittleEndian(content, id);
    putString(content, name);
    putString(content, encoding);
    putString(content, data);
    schemaRecords_.push_back(record(kSchema, content));
    chunk_ += schemaRecords_.back();
    return id;
}

uint16_t McapWriter::addChannel(uint16_t schemaId, const std::string& topic, const std::string& messageEncoding,
                                const std::map<std::string, std::string>& metadata) {
    const uint16_t id = uint16_t(channelRecords_.size());
    std::string content, map;
    appendLittleEndian(content, id, schemaId);
    putString(content, topic);
    putString(content, messageEncoding);
    for (const auto& [key, value] : metadata) putString(map, key), putString(map, value);
    putString(content, map); // a map is its byte length and its entries, as a string is
    channelRecords_.push_back(record(kChannel, content));
    channelCounts_.push_back(0);
    chunk_ += channelRecords_.back();
    return id;
}

void McapWriter::addMessage(uint16_t channelId, uint64_t logTime, uint64_t publishTime, const std::string& data) {
    std::string content;
    appendLittleEndian(content, channelId, uint32_t(channelCounts_.at(channelId)++), logTime, publishTime);
    chunkMessages_[channelId].emplace_back(logTime, chunk_.size());
    chunk_ += record(kMessage, content + data);
    chunkStart_ = std::min(chunkStart_, logTime), chunkEnd_ = std::max(chunkEnd_, logTime);
    startTime_ = std::min(startTime_, logTime), endTime_ = std::max(endTime_, logTime);
    ++messageCount_;
}

void McapWriter::flushChunk() {
    if (chunk_.empty()) return;
    const bool hasMessages = !chunkMessages_.empty();
    ChunkIndex index{.startTime = hasMessages ? chunkStart_ : 0,
                     .endTime = hasMessages ? chunkEnd_ : 0,
                     .offset = position_,
                     .length = 0,
                     .indexLength = 0,
                     .recordsSize = chunk_.size()};
    std::string content;
    appendLittleEndian(content, index.startTime, index.endTime, uint64_t(chunk_.size()), crc32(chunk_));
    putString(content, ""); // uncompressed
    appendLittleEndian(content, uint64_t(chunk_.size()));
    const std::string chunk = record(kChunk, content + chunk_);
    index.length = chunk.size();
    write(chunk, true);
    for (const auto& [channel, entries] : chunkMessages_) {
        index.indexOffsets[channel] = position_;
        const std::string indexRecord = messageIndexRecord(channel, entries);
        index.indexLength += indexRecord.size();
        write(indexRecord, true);
    }
    chunks_.push_back(index);
    chunk_.clear(), chunkMessages_.clear();
    chunkStart_ = UINT64_MAX, chunkEnd_ = 0;
}

void McapWriter::finish() {
    flushChunk();
    std::string dataEnd;
    appendLittleEndian(dataEnd, ~dataCrc_);
    write(record(kDataEnd, dataEnd), false);

    std::string statistics;
    const bool any = messageCount_ > 0;
    appendLittleEndian(statistics, messageCount_, uint16_t(schemaRecords_.size()), uint32_t(channelRecords_.size()),
                       uint32_t(0), uint32_t(0), uint32_t(chunks_.size()), any ? startTime_ : 0, any ? endTime_ : 0);
    std::string counts;
    for (size_t c = 0; c < channelCounts_.size(); ++c) appendLittleEndian(counts, uint16_t(c), channelCounts_[c]);
    putString(statistics, counts);
    std::vector<std::string> chunkIndexes;
    for (const ChunkIndex& chunk : chunks_) {
        std::string content, offsets;
        appendLittleEndian(content, chunk.startTime, chunk.endTime, chunk.offset, chunk.length);
        for (const auto& [channel, offset] : chunk.indexOffsets) appendLittleEndian(offsets, channel, offset);
        putString(content, offsets);
        appendLittleEndian(content, chunk.indexLength);
        putString(content, "");
        appendLittleEndian(content, chunk.recordsSize, chunk.recordsSize);
        chunkIndexes.push_back(record(kChunkIndex, content));
    }

    // The summary, one group per opcode, and where each group starts (the Summary Offset records).
    const uint64_t summaryStart = position_;
    std::string summary, offsets;
    auto group = [&](Opcode opcode, const std::vector<std::string>& records) {
        const uint64_t start = summaryStart + summary.size();
        for (const std::string& r : records) summary += r;
        std::string offset(1, char(opcode));
        appendLittleEndian(offset, start, uint64_t(summaryStart + summary.size() - start));
        if (!records.empty()) offsets += record(kSummaryOffset, offset);
    };
    group(kSchema, schemaRecords_);
    group(kChannel, channelRecords_);
    group(kStatistics, {record(kStatistics, statistics)});
    group(kChunkIndex, chunkIndexes);
    std::string footer(1, char(kFooter));
    appendLittleEndian(footer, uint64_t(20), summaryStart, uint64_t(summaryStart + summary.size()));
    // The summary CRC covers the summary, its offsets and the footer up to the CRC itself.
    const std::string summarised = summary + offsets + footer;
    appendLittleEndian(footer, crc32(summarised));
    write(summary + offsets + footer + std::string(kMagic, 8), false);
    std::FILE* file = file_;
    file_ = nullptr;
    if (std::fclose(file) != 0) throw Error("cannot write '" + path_ + "': " + ioErrorReason(errno));
}

void McapWriter::write(const std::string& bytes, bool dataSection) {
    if (dataSection) dataCrc_ = crcUpdate(dataCrc_, bytes);
    if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
        throw Error("cannot write '" + path_ + "': " + ioErrorReason(errno));
    position_ += bytes.size();
}

} // namespace sward
