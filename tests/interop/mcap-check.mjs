// SPDX-License-Identifier: Apache-2.0
// Reads an MCAP file of `flatsat export --mcap` with published readers no one
// here wrote, and compares what they decode with flatsat's own export:
//   node mcap-check.mjs FILE.mcap JSON_DIR INFO_SQLITE.json INFO_MCAP.json
// JSON_DIR: `flatsat export REC --json` of the same recording; the two info
// files: `flatsat info --json` of the recording and of the MCAP file.
// Prints one line per check and "mcap-check: N checks passed"; exits 1 on the first failure.
import { readFileSync } from "node:fs";
import { join } from "node:path";
import { crc32 } from "@foxglove/crc";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { loadDecompressHandlers } from "@mcap/support";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";

const [file, jsonDir, infoSqlitePath, infoMcapPath] = process.argv.slice(2);
let checks = 0;
function check(ok, what) {
  if (!ok) {
    console.error(`mcap-check: FAILED: ${what}`);
    process.exit(1);
  }
  ++checks;
}

const bytes = new Uint8Array(readFileSync(file));
const decompressHandlers = await loadDecompressHandlers();

// 1. Every record in file order, chunk CRCs checked (McapStreamReader).
const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
stream.append(bytes);
const streamed = new Map(); // channel id -> messages in file order
const channels = new Map();
const schemas = new Map();
let records = 0;
for (let record; (record = stream.nextRecord()); ) {
  ++records;
  if (record.type === "Schema") schemas.set(record.id, record);
  if (record.type === "Channel") channels.set(record.id, record);
  if (record.type === "Message") {
    if (!streamed.has(record.channelId)) streamed.set(record.channelId, []);
    streamed.get(record.channelId).push(record);
  }
}
check(stream.done(), "the stream reader reached the closing magic");
console.log(`records read in order: ${records}, channels ${channels.size}`);

// 2. The summary, its CRC, the chunk and message indexes (McapIndexedReader).
const readable = {
  size: async () => BigInt(bytes.length),
  read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
};
const indexed = await McapIndexedReader.Initialize({ readable, decompressHandlers });
check(indexed.chunkIndexes.length > 0, "chunk indexes in the summary");
check(indexed.statistics !== undefined, "a statistics record");
const dataEnd = indexed.dataSectionCrc;
check(dataEnd === 0 || dataEnd === crc32(bytes.subarray(0, Number(indexed.dataEndOffset))),
      "the data section's CRC (DataEnd) over every byte before it");
const byIndex = new Map();
let indexedCount = 0;
let lastTime = -1n;
for await (const message of indexed.readMessages()) {
  ++indexedCount;
  check(message.logTime >= lastTime, "indexed messages in log-time order");
  lastTime = message.logTime;
  byIndex.set(message.channelId, (byIndex.get(message.channelId) ?? 0) + 1);
}
check(BigInt(indexedCount) === indexed.statistics.messageCount, "indexed message count = statistics");
for (const [id, list] of streamed) {
  check(byIndex.get(id) === list.length, `channel ${channels.get(id).topic}: the index finds every message`);
  check(indexed.statistics.channelMessageCounts.get(id) === BigInt(list.length),
        `channel ${channels.get(id).topic}: statistics count`);
}

// 3. Counts equal flatsat info's, of the recording and of the file itself.
const infoSqlite = JSON.parse(readFileSync(infoSqlitePath, "utf8"));
const infoMcap = JSON.parse(readFileSync(infoMcapPath, "utf8"));
const topicCount = new Map([...channels.values()].map((c) => [c.topic, streamed.get(c.id)?.length ?? 0]));
for (const t of infoSqlite.topics) {
  check(topicCount.get(t.name) === t.count, `${t.name}: ${topicCount.get(t.name)} messages, info says ${t.count}`);
}
for (const t of infoMcap.topics) check(topicCount.get(t.name) === t.count, `info of the MCAP file: ${t.name}`);
const metadata = [];
for await (const m of indexed.readMetadata({ name: "flatsat" })) metadata.push(m);
check(metadata.length === 1, "one flatsat metadata record");
check(metadata[0].metadata.get("recording_sha256") === infoSqlite.recording_sha256, "metadata recording_sha256");
check(infoMcap.recording_sha256 === infoSqlite.recording_sha256, "info of the MCAP file: recording_sha256");

// 4. Every CDR message of every channel decoded with its omgidl schema equals
//    `flatsat export --json` of the same recording, field by field.
function enumsOf(idl) {
  const enums = new Map();
  for (const m of idl.replace(/\/\/[^\n]*/g, "").matchAll(/enum\s+(\w+)\s*\{([^}]*)\}/g)) {
    enums.set(m[1], m[2].split(",").map((s) => s.trim()).filter(Boolean));
  }
  return enums;
}
function same(expected, decoded, path, enumNames) {
  if (typeof expected === "string") {
    if (typeof decoded === "number" && enumNames.some((names) => names[decoded] === expected)) return;
    if (typeof decoded === "string") return check(decoded === expected, `${path}: "${decoded}" vs "${expected}"`);
    // char[N]: the bytes up to the first NUL.
    const chars = Array.from(decoded, (c) => (typeof c === "number" ? String.fromCharCode(c) : c)).join("");
    return check(chars.split("\0")[0] === expected, `${path}: "${chars}" vs "${expected}"`);
  }
  if (typeof expected === "boolean") return check(decoded === expected, `${path}: ${decoded} vs ${expected}`);
  if (typeof expected === "number") {
    // JSON.parse reads 64-bit integers as the nearest double, as Number() does to the decoder's bigint;
    // a float field's JSON text is the float's shortest, the decoder's value the float itself.
    const d = Number(decoded);
    return check(d === expected || Math.fround(expected) === d, `${path}: ${d} vs ${expected}`);
  }
  if (Array.isArray(expected)) {
    const list = Array.from(decoded);
    check(list.length === expected.length, `${path}: ${list.length} elements vs ${expected.length}`);
    expected.forEach((e, i) => same(e, list[i], `${path}[${i}]`, enumNames));
    return;
  }
  for (const key of Object.keys(expected)) same(expected[key], decoded[key], `${path}.${key}`, enumNames);
}
let decodedCount = 0;
for (const channel of channels.values()) {
  const schema = schemas.get(channel.schemaId);
  if (schema.encoding !== "omgidl") continue;
  check(channel.messageEncoding === "cdr", `${channel.topic}: message encoding cdr`);
  const idl = new TextDecoder().decode(schema.data);
  const reader = new MessageReader(schema.name, parseIDL(idl));
  const enumNames = [...enumsOf(idl).values()];
  const short = channel.topic.replace(/^flatsat\//, "");
  const lines = readFileSync(join(jsonDir, `${short}.jsonl`), "utf8").trim().split("\n");
  const messages = streamed.get(channel.id) ?? [];
  check(messages.length === lines.length, `${channel.topic}: ${messages.length} messages, export has ${lines.length}`);
  messages.forEach((m, i) => {
    same(JSON.parse(lines[i]), reader.readMessage(m.data), `${channel.topic}#${i}`, enumNames);
    ++decodedCount;
  });
}
console.log(`CDR messages decoded and equal to flatsat export --json: ${decodedCount}`);

// 5. The derived FrameTransform channel: unit quaternions, the truth's attitude.
const tf = [...channels.values()].find((c) => c.topic === "flatsat/tf/truth");
check(tf && schemas.get(tf.schemaId).name === "foxglove.FrameTransform" && tf.messageEncoding === "json",
      "flatsat/tf/truth is foxglove.FrameTransform in JSON");
const truthLines = readFileSync(join(jsonDir, "truth.jsonl"), "utf8").trim().split("\n");
const frames = streamed.get(tf.id);
check(frames.length === truthLines.length, "a transform per truth sample");
frames.forEach((m, i) => {
  const t = JSON.parse(new TextDecoder().decode(m.data));
  const q = JSON.parse(truthLines[i]).q_inertial_body;
  const r = t.rotation;
  check(Math.abs(Math.hypot(r.x, r.y, r.z, r.w) - 1) < 1e-9, `transform ${i}: |q| = 1`);
  check(r.w === q[0] && r.x === q[1] && r.y === q[2] && r.z === q[3], `transform ${i}: the truth's q_inertial_body`);
  check(t.parent_frame_id === "inertial" && t.child_frame_id === "body", `transform ${i}: frames`);
  check(BigInt(t.timestamp.sec) * 1000000000n + BigInt(t.timestamp.nsec) === m.logTime, `transform ${i}: time`);
});
const log = [...channels.values()].find((c) => c.topic === "flatsat/log");
check(log && schemas.get(log.schemaId).name === "foxglove.Log", "flatsat/log is foxglove.Log");
for (const m of streamed.get(log.id) ?? []) {
  const entry = JSON.parse(new TextDecoder().decode(m.data));
  check(entry.level >= 1 && entry.level <= 5 && entry.name.length > 0, "a log entry with a level and a name");
}
console.log(`mcap-check: ${checks} checks passed`);
