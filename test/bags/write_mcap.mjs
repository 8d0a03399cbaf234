#!/usr/bin/env node
// Writes an MCAP file of velodyne_msgs/msg/VelodyneScan (CDR) from a pcap with the reference MCAP
// library (npm @mcap/core), chunks compressed by @foxglove/wasm-zstd or lz4js (LZ4 frames).
//
// Usage: write_mcap.mjs PCAP OUT.mcap none|zstd|lz4|unchunked [TOPIC]
// Exit 77 (a skip for ctest) when the npm packages are not installed (scripts/install-deps.sh).
// The pcap parsing and the CDR encoding are written here, independent of conicloc's readers.
import { createRequire } from "node:module";
import { open, readFile } from "node:fs/promises";
import path from "node:path";
import { fileURLToPath } from "node:url";

import { Cdr } from "./cdr_writer.mjs";

const require = createRequire(path.join(path.dirname(fileURLToPath(import.meta.url)), "../js/"));
const [pcapPath, outPath, compression, topic = "/velodyne_packets"] = process.argv.slice(2);

let mcap, zstd, lz4;
try {
  mcap = require("@mcap/core");
  zstd = require("@foxglove/wasm-zstd");
  lz4 = require("lz4js");
} catch (e) {
  console.log(`SKIP: the MCAP writer is not installed (${e.code}); run scripts/install-deps.sh`);
  process.exit(77);
}

const DATA_PORT = 2368;
const PACKET_BYTES = 1206;
const PACKETS_PER_SCAN = 76;

// Data packets of a classic pcap (Ethernet / IPv4 / UDP): [sec, nsec, payload].
function dataPackets(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const magic = view.getUint32(0, true);
  const little = magic === 0xa1b2c3d4 || magic === 0xa1b23c4d;
  if (!little && view.getUint32(0, false) !== 0xa1b2c3d4 && view.getUint32(0, false) !== 0xa1b23c4d)
    throw new Error("not a classic pcap");
  const nano = view.getUint32(0, little) === 0xa1b23c4d;
  const packets = [];
  for (let at = 24; at + 16 <= bytes.length; ) {
    const sec = view.getUint32(at, little);
    const frac = view.getUint32(at + 4, little);
    const captured = view.getUint32(at + 8, little);
    const frame = bytes.subarray(at + 16, at + 16 + captured);
    at += 16 + captured;
    if (frame.length < 42 || frame[12] !== 0x08 || frame[13] !== 0x00 || frame[23] !== 17) continue;
    const udp = frame.subarray(14 + (frame[14] & 0x0f) * 4);
    const dstPort = (udp[2] << 8) | udp[3];
    const length = (udp[4] << 8) | udp[5];
    const payload = udp.subarray(8, length);
    if (dstPort === DATA_PORT && payload.length === PACKET_BYTES)
      packets.push([sec, nano ? frac : frac * 1000, payload]);
  }
  return packets;
}

function velodyneScan(group) {
  const cdr = new Cdr();
  const [sec, nsec] = group[group.length - 1];
  cdr.i32(sec);
  cdr.u32(nsec);
  cdr.string("velodyne");
  cdr.u32(group.length);
  for (const [s, ns, payload] of group) {
    cdr.i32(s);
    cdr.u32(ns);
    cdr.bytes(payload);
  }
  return cdr.message();
}

const SCAN_SCHEMA = `std_msgs/Header header
VelodynePacket[] packets
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
================================================================================
MSG: velodyne_msgs/VelodynePacket
builtin_interfaces/Time stamp
uint8[1206] data
`;

await zstd.isLoaded;
const compressors = {
  none: undefined,
  unchunked: undefined,
  zstd: (data) => ({ compression: "zstd", compressedData: zstd.compress(data, 3) }),
  lz4: (data) => ({ compression: "lz4", compressedData: lz4.compress(data) }),
};
if (!(compression in compressors)) throw new Error(`unknown mode ${compression}`);

const file = await open(outPath, "w");
let position = 0n;
const writable = {
  position: () => position,
  write: async (buffer) => {
    await file.write(buffer);
    position += BigInt(buffer.length);
  },
};
const writer = new mcap.McapWriter({
  writable,
  useChunks: compression !== "unchunked",
  chunkSize: 256 * 1024,
  compressChunk: compressors[compression],
});
await writer.start({ profile: "ros2", library: "conicloc test writer (@mcap/core)" });
const text = (s) => new TextEncoder().encode(s);
const scanSchema = await writer.registerSchema({
  name: "velodyne_msgs/msg/VelodyneScan",
  encoding: "ros2msg",
  data: text(SCAN_SCHEMA),
});
const stringSchema = await writer.registerSchema({
  name: "std_msgs/msg/String",
  encoding: "ros2msg",
  data: text("string data\n"),
});
const scans = await writer.registerChannel({
  topic,
  schemaId: scanSchema,
  messageEncoding: "cdr",
  metadata: new Map(),
});
const notes = await writer.registerChannel({
  topic: "/notes",
  schemaId: stringSchema,
  messageEncoding: "cdr",
  metadata: new Map(),
});

const packets = dataPackets(await readFile(pcapPath));
let sequence = 0;
for (let i = 0; i < packets.length; i += PACKETS_PER_SCAN) {
  const group = packets.slice(i, i + PACKETS_PER_SCAN);
  const [sec, nsec] = group[group.length - 1];
  const time = BigInt(sec) * 1000000000n + BigInt(nsec);
  await writer.addMessage({
    channelId: scans,
    sequence: sequence++,
    logTime: time,
    publishTime: time,
    data: velodyneScan(group),
  });
  const note = new Cdr();
  note.string(`scan ${sequence}`);
  await writer.addMessage({ channelId: notes, sequence, logTime: time, publishTime: time, data: note.message() });
}
await writer.end();
await file.close();
console.log(`${outPath}: ${packets.length} packets, ${compression}`);
