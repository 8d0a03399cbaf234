#!/usr/bin/env node
// Reads a `conicloc localize --record` file with the reference MCAP library (npm @mcap/core) and
// checks what Foxglove and Lichtblick rely on: the index (McapIndexedReader: footer, summary,
// summary offsets, statistics, chunk indexes, every CRC), the schemas and channels, one message
// per scan on every topic (the map once), and every message as JSON against its schema: every
// field the schema names, the required ones present, the point data as long as point_stride says,
// the estimate and the frame transform equal to the poses of `--out`.
//
// Usage: check_recording.mjs RUN.mcap POSES.tum
// Exit 77 (a skip for ctest) when the npm packages are not installed (scripts/install-deps.sh).
import { createRequire } from "node:module";
import { open, readFile } from "node:fs/promises";
import path from "node:path";
import { fileURLToPath } from "node:url";
import zlib from "node:zlib";

const require = createRequire(path.join(path.dirname(fileURLToPath(import.meta.url)), "../js/"));
const [recordingPath, posesPath] = process.argv.slice(2);

let mcap, zstd;
try {
  mcap = require("@mcap/core");
  zstd = require("@foxglove/wasm-zstd");
} catch (e) {
  console.log(`SKIP: the MCAP reader is not installed (${e.code}); run scripts/install-deps.sh`);
  process.exit(77);
}
await zstd.isLoaded;
const decompressHandlers = { zstd: (data, size) => zstd.decompress(data, Number(size)) };

let failures = 0;
function check(condition, what) {
  if (!condition) {
    failures += 1;
    if (failures <= 20) console.log(`FAIL: ${what}`);
  }
}

const expected = {
  "/map": "foxglove.SceneUpdate",
  "/scan": "foxglove.PointCloud",
  "/particles": "foxglove.PosesInFrame",
  "/estimate": "foxglove.PoseInFrame",
  "/conics": "foxglove.SceneUpdate",
  "/tf": "foxglove.FrameTransform",
};

// The poses of `localize --out` (TUM: time x y z qx qy qz qw), by time in nanoseconds.
const poses = (await readFile(posesPath, "utf8"))
  .split("\n")
  .filter((line) => line.trim() && !line.startsWith("#"))
  .map((line) => line.trim().split(/\s+/).map(Number));
const scans = poses.length;

const handle = await open(recordingPath, "r");
const readable = {
  size: async () => BigInt((await handle.stat()).size),
  read: async (offset, size) => {
    const buffer = new Uint8Array(Number(size));
    await handle.read(buffer, 0, Number(size), Number(offset));
    return buffer;
  },
};
const reader = await mcap.McapIndexedReader.Initialize({ readable, decompressHandlers });

check(reader.header.library === "conicloc", `header library '${reader.header.library}'`);
check(reader.chunkIndexes.length > 0, "no chunk indexes");
for (const opcode of [mcap.Opcode.SCHEMA, mcap.Opcode.CHANNEL, mcap.Opcode.STATISTICS,
  mcap.Opcode.CHUNK_INDEX]) {
  check(reader.summaryOffsetsByOpcode.has(opcode), `no summary offset for opcode ${opcode}`);
}
const whole = await readFile(recordingPath);
check(reader.dataSectionCrc === zlib.crc32(whole.subarray(0, Number(reader.dataEndOffset))),
  "data section CRC");

// Channels and schemas; each schema a JSON schema titled by its name.
const schemaOf = new Map();  // topic -> parsed JSON schema
for (const channel of reader.channelsById.values()) {
  const schema = reader.schemasById.get(channel.schemaId);
  check(expected[channel.topic] === schema?.name, `${channel.topic}: schema '${schema?.name}'`);
  check(channel.messageEncoding === "json", `${channel.topic}: encoding ${channel.messageEncoding}`);
  check(schema?.encoding === "jsonschema", `${channel.topic}: schema encoding ${schema?.encoding}`);
  const parsed = JSON.parse(new TextDecoder().decode(schema.data));
  check(parsed.title === schema.name, `${channel.topic}: schema title ${parsed.title}`);
  schemaOf.set(channel.topic, parsed);
}
check(schemaOf.size === Object.keys(expected).length, `${schemaOf.size} channels`);

// What Foxglove's and Lichtblick's JSON-schema parser (mcap-support parseJsonSchema) accepts:
// every object lists its "properties", every field has a type it knows or is an enum of numbers,
// bytes are base64 strings.
function parsable(schema, where) {
  check(schema.type === "object" && typeof schema.properties === "object",
    `${where}: an object schema without properties`);
  for (const [name, field] of Object.entries(schema.properties ?? {})) {
    const at = `${where}.${name}`;
    if (Array.isArray(field.oneOf)) {
      check(field.oneOf.every((o) => typeof o.const === "number"), `${at}: enum values`);
    } else if (field.type === "object") {
      parsable(field, at);
    } else if (field.type === "array") {
      const item = field.items ?? {};
      if (item.type === "object") parsable(item, `${at}[]`);
      else check(["boolean", "string", "number", "integer"].includes(item.type), `${at}[]: type`);
      check(item.contentEncoding === undefined, `${at}[]: contentEncoding`);
    } else {
      check(["boolean", "string", "number", "integer"].includes(field.type), `${at}: type`);
      check(field.contentEncoding === undefined ||
        (field.type === "string" && field.contentEncoding === "base64"), `${at}: contentEncoding`);
    }
  }
}
for (const [topic, schema] of schemaOf) parsable(schema, topic);
check(schemaOf.get("/scan").properties.data.contentEncoding === "base64", "PointCloud data base64");

// Statistics: the map once, one message per scan on every other topic.
const countOf = (topic) => {
  const [id] = [...reader.channelsById].find(([, c]) => c.topic === topic) ?? [];
  return Number(reader.statistics?.channelMessageCounts.get(id) ?? -1);
};
for (const topic of Object.keys(expected)) {
  check(countOf(topic) === (topic === "/map" ? 1 : scans),
    `${topic}: ${countOf(topic)} messages in the statistics, ${scans} scans`);
}
check(Number(reader.statistics.messageCount) === 5 * scans + 1, "statistics message count");

// Every field of a message is one its schema names (recursively), with the JSON type it says.
function conforms(value, schema, where) {
  if (schema.oneOf) return check(schema.oneOf.some((o) => o.const === value), `${where}: ${value}`);
  switch (schema.type) {
    case "object":
      check(typeof value === "object" && value !== null && !Array.isArray(value), `${where}: object`);
      for (const [key, item] of Object.entries(value)) {
        const field = schema.properties?.[key];
        check(field !== undefined || !schema.properties, `${where}.${key} is not in the schema`);
        if (field) conforms(item, field, `${where}.${key}`);
      }
      break;
    case "array":
      check(Array.isArray(value), `${where}: array`);
      value.forEach((item, i) => conforms(item, schema.items, `${where}[${i}]`));
      break;
    case "number":
      check(Number.isFinite(value), `${where}: number`);
      break;
    case "integer":
      check(Number.isInteger(value) && value >= (schema.minimum ?? -Infinity), `${where}: integer`);
      break;
    case "string":
      check(typeof value === "string", `${where}: string`);
      break;
    case "boolean":
      check(typeof value === "boolean", `${where}: boolean`);
      break;
    default:
      check(false, `${where}: schema type ${schema.type}`);
  }
}

const near = (a, b, tolerance) => Math.abs(a - b) <= tolerance;
const unit = (q) => near(Math.hypot(q.x, q.y, q.z, q.w), 1, 1e-9);
// The same pose as the TUM row, to the recording's 0.1 mm and the TUM file's 9 digits.
function samePose(pose, row, where) {
  const [, x, y, z, qx, qy, qz, qw] = row;
  const p = pose.position ?? pose.translation;
  const q = pose.orientation ?? pose.rotation;
  const sign = Math.sign(q.w * qw + q.x * qx + q.y * qy + q.z * qz) || 1;  // q and -q: one turn
  check(near(p.x, x, 1e-4) && near(p.y, y, 1e-4) && near(p.z, z, 1e-4), `${where}: position`);
  check([q.x - sign * qx, q.y - sign * qy, q.z - sign * qz, q.w - sign * qw].every(
    (d) => Math.abs(d) < 1e-6), `${where}: orientation`);
}

const seen = Object.fromEntries(Object.keys(expected).map((topic) => [topic, 0]));
const topicOf = new Map([...reader.channelsById].map(([id, c]) => [id, c.topic]));
let points = 0, particles = 0, triangles = 0, conicLines = 0;
for await (const message of reader.readMessages()) {
  const topic = topicOf.get(message.channelId);
  const index = seen[topic]++;
  const where = `${topic} #${index}`;
  const m = JSON.parse(new TextDecoder().decode(message.data));
  conforms(m, schemaOf.get(topic), where);
  const stamp = m.timestamp ?? m.entities?.[0]?.timestamp;
  check(stamp && BigInt(stamp.sec) * 1000000000n + BigInt(stamp.nsec) === message.logTime,
    `${where}: timestamp is not the log time`);
  const row = poses[topic === "/map" ? 0 : index];
  check(near(Number(message.logTime) / 1e9, row[0], 1e-6), `${where}: log time ${message.logTime}`);
  switch (topic) {
    case "/scan": {
      const data = Buffer.from(m.data, "base64");
      check(m.frame_id === "sensor", `${where}: frame ${m.frame_id}`);
      check(m.point_stride === 18, `${where}: stride ${m.point_stride}`);
      check(m.fields.map((f) => `${f.name}:${f.offset}:${f.type}`).join(",") ===
        "x:0:7,y:4:7,z:8:7,intensity:12:7,ring:16:3", `${where}: fields`);
      check(data.length > 0 && data.length % m.point_stride === 0, `${where}: ${data.length} bytes`);
      for (let at = 0; at + m.point_stride <= data.length; at += m.point_stride) {
        const range = Math.hypot(data.readFloatLE(at), data.readFloatLE(at + 4), data.readFloatLE(at + 8));
        const ring = data.readUInt16LE(at + 16);
        check(range > 0.1 && range < 130 && ring < 16, `${where}: point at byte ${at}`);
      }
      points += data.length / m.point_stride;
      break;
    }
    case "/particles":
      check(m.frame_id === "map" && m.poses.length > 0 && m.poses.length <= 500,
        `${where}: ${m.poses.length} poses in ${m.frame_id}`);
      check(m.poses.every((p) => unit(p.orientation)), `${where}: quaternions`);
      particles += m.poses.length;
      break;
    case "/estimate":
      check(m.frame_id === "map", `${where}: frame ${m.frame_id}`);
      samePose(m.pose, row, where);
      break;
    case "/tf":
      check(m.parent_frame_id === "map" && m.child_frame_id === "sensor", `${where}: frames`);
      samePose(m, row, where);
      break;
    case "/map":
    case "/conics": {
      check(m.entities.length === 1, `${where}: ${m.entities.length} entities`);
      const entity = m.entities[0];
      check(entity.frame_id === (topic === "/map" ? "map" : "sensor"), `${where}: frame`);
      if (topic === "/map") {
        check(entity.triangles.length > 0, `${where}: no triangle lists`);
        for (const list of entity.triangles) {
          check(list.points.length % 3 === 0, `${where}: ${list.points.length} triangle points`);
          triangles += list.points.length / 3;
        }
      } else {
        check(entity.lines.length > 0, `${where}: no lines`);
        for (const line of entity.lines) {
          check(line.type === 0 && line.points.length >= 2, `${where}: line`);
          // Points of a ring's conic: beyond the minimum range, within the maximum.
          check(line.points.every((p) => { const r = Math.hypot(p.x, p.y, p.z); return r > 0.2 && r < 101; }),
            `${where}: conic point range`);
        }
        conicLines += entity.lines.length;
      }
      break;
    }
  }
}
for (const topic of Object.keys(expected)) {
  check(seen[topic] === countOf(topic), `${topic}: ${seen[topic]} messages read`);
}

// The same file front to back without the index (McapStreamReader): the same message count.
const stream = new mcap.McapStreamReader({ decompressHandlers });
stream.append(whole);
let streamed = 0, dataEnd = false;
for (let record; (record = stream.nextRecord()); ) {
  if (record.type === "Message") streamed += 1;
  if (record.type === "DataEnd") dataEnd = true;
}
check(stream.done(), "stream reader: not done at the end");
check(dataEnd && streamed === 5 * scans + 1, `stream reader: ${streamed} messages`);

await handle.close();
console.log(`${scans} scans: ${points} points, ${particles} particle poses, ${triangles} map ` +
  `triangles, ${conicLines} conic lines; ${reader.chunkIndexes.length} chunks, ` +
  `${whole.length} bytes`);
if (failures > 0) {
  console.log(`FAIL: ${failures} checks failed`);
  process.exit(1);
}
console.log("PASS: the recording reads back with @mcap/core");
