// Reads a ROS 2 bag in MCAP form (sward-export --layout ros2) with Foxglove's readers only, as a ROS 2 user's tool
// would: @mcap/core's indexed reader (footer, summary, chunk and message indexes, every CRC) and its stream reader
// (every record in file order), @foxglove/rosmsg for the embedded "ros2msg" definitions and
// @foxglove/rosmsg2-serialization for the CDR. Every message must decode using exactly its bytes.
//
//     node read_bag.mjs BAG.mcap OUT
// Writes OUT/messages.jsonl (one decoded message per line, in log-time order: topic, schema, log_time, sequence,
// message) and OUT/N.bin for each uint8[] field (the line holds {"bin": "N.bin"}); non-finite floats as strings.
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { parse } from "@foxglove/rosmsg";
import { MessageReader } from "@foxglove/rosmsg2-serialization";
import { open, readFile, writeFile } from "node:fs/promises";
import path from "node:path";

const [bagPath, outDir] = process.argv.slice(2);
if (!bagPath || !outDir) {
  console.error("usage: node read_bag.mjs BAG.mcap OUT");
  process.exit(2);
}

const handle = await open(bagPath, "r");
const readable = {
  size: async () => BigInt((await handle.stat()).size),
  read: async (offset, size) => {
    const buffer = new Uint8Array(Number(size));
    const { bytesRead } = await handle.read(buffer, 0, buffer.length, Number(offset));
    if (bytesRead !== buffer.length) throw new Error(`short read at ${offset}`);
    return buffer;
  },
};
const reader = await McapIndexedReader.Initialize({ readable });
if (reader.header.profile !== "ros2") throw new Error(`profile '${reader.header.profile}', expected ros2`);

const decoders = new Map();
for (const channel of reader.channelsById.values()) {
  const schema = reader.schemasById.get(channel.schemaId);
  if (channel.messageEncoding !== "cdr" || schema.encoding !== "ros2msg")
    throw new Error(`${channel.topic}: ${channel.messageEncoding} / ${schema.encoding}, expected cdr / ros2msg`);
  if (!("offered_qos_profiles" in Object.fromEntries(channel.metadata)))
    throw new Error(`${channel.topic}: no offered_qos_profiles (the ros2 profile requires it)`);
  const definitions = parse(new TextDecoder().decode(schema.data), { ros2: true });
  decoders.set(channel.id, { topic: channel.topic, schema: schema.name, reader: new MessageReader(definitions) });
}

let bins = 0;
const lines = [];
const pending = [];
function plain(value) {
  if (value instanceof Uint8Array || value instanceof Int8Array) {
    const name = `${bins++}.bin`;
    pending.push(writeFile(path.join(outDir, name), value));
    return { bin: name };
  }
  if (ArrayBuffer.isView(value)) return Array.from(value, plain);
  if (Array.isArray(value)) return value.map(plain);
  if (typeof value === "bigint") return value.toString();
  if (typeof value === "number" && !Number.isFinite(value)) return String(value);
  if (value && typeof value === "object")
    return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, plain(v)]));
  return value;
}

for await (const message of reader.readMessages()) {
  const decoder = decoders.get(message.channelId);
  const decoded = decoder.reader.readMessage(message.data);
  if (decoder.reader.lastReadHadTrailingBytes() || decoder.reader.lastReadByteLength() !== message.data.length)
    throw new Error(`${decoder.topic} #${message.sequence}: decoded ${decoder.reader.lastReadByteLength()} of ` +
                    `${message.data.length} bytes`);
  lines.push(JSON.stringify({
    topic: decoder.topic,
    schema: decoder.schema,
    log_time: message.logTime.toString(),
    sequence: message.sequence,
    message: plain(decoded),
  }));
}
await Promise.all(pending);
await handle.close();

// The same file front to back: every record parses, chunk CRCs hold, and it holds as many messages.
const stream = new McapStreamReader();
stream.append(await readFile(bagPath));
let streamed = 0, record;
while ((record = stream.nextRecord())) if (record.type === "Message") ++streamed;
if (!stream.done()) throw new Error("the stream reader did not reach the trailing magic");
const stats = reader.statistics;
if (streamed !== lines.length || !stats || Number(stats.messageCount) !== lines.length)
  throw new Error(`${lines.length} indexed, ${streamed} streamed, statistics ${stats?.messageCount} messages`);

await writeFile(path.join(outDir, "messages.jsonl"), lines.join("\n") + "\n");
console.log(`read_bag: ${lines.length} messages on ${decoders.size} channels decoded`);
