#!/usr/bin/env node
// Writes an MCAP file of sensor_msgs/msg/PointCloud2 (CDR, zstd chunks), one cloud per rotation as
// the ROS Velodyne driver publishes them, with the reference MCAP library (npm @mcap/core).
//
// Usage: write_cloud_mcap.mjs PCAP POINTS.csv OUT.mcap
// POINTS.csv is `conicloc decode PCAP --csv` (device times, seconds past the hour); the hour is the
// pcap's first data packet's capture time less its µs-past-the-hour stamp. Each cloud is stamped
// with its first firing; `time` is seconds after the stamp. Fields x y z intensity (float32), ring
// (uint16), time (float32), packed as the driver lays them out (22 bytes a point).
// Exit 77 (a skip for ctest) when the npm packages are not installed (scripts/install-deps.sh).
// The CDR encoding is written here, independent of conicloc's readers.
import { createRequire } from "node:module";
import { open, readFile } from "node:fs/promises";
import path from "node:path";
import { fileURLToPath } from "node:url";

import { Cdr } from "./cdr_writer.mjs";

const require = createRequire(path.join(path.dirname(fileURLToPath(import.meta.url)), "../js/"));
const [pcapPath, csvPath, outPath] = process.argv.slice(2);

let mcap, zstd;
try {
  mcap = require("@mcap/core");
  zstd = require("@foxglove/wasm-zstd");
} catch (e) {
  console.log(`SKIP: the MCAP writer is not installed (${e.code}); run scripts/install-deps.sh`);
  process.exit(77);
}

// UTC of the device clock's hour, from the first data packet (port 2368) of a classic pcap.
function hourBase(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const little = view.getUint32(0, true) === 0xa1b2c3d4 || view.getUint32(0, true) === 0xa1b23c4d;
  const nano = view.getUint32(0, little) === 0xa1b23c4d;
  for (let at = 24; at + 16 <= bytes.length; ) {
    const sec = view.getUint32(at, little);
    const frac = view.getUint32(at + 4, little);
    const captured = view.getUint32(at + 8, little);
    const frame = bytes.subarray(at + 16, at + 16 + captured);
    at += 16 + captured;
    if (frame.length < 42 || frame[12] !== 0x08 || frame[13] !== 0x00 || frame[23] !== 17) continue;
    const udp = frame.subarray(14 + (frame[14] & 0x0f) * 4);
    const payload = udp.subarray(8, (udp[4] << 8) | udp[5]);
    if (((udp[2] << 8) | udp[3]) !== 2368 || payload.length !== 1206) continue;
    const stampUs = new DataView(payload.buffer, payload.byteOffset).getUint32(1200, true);
    const capture = sec + (nano ? frac * 1e-9 : frac * 1e-6);
    return Math.round((capture - stampUs * 1e-6) / 3600) * 3600;
  }
  throw new Error("no data packet in the pcap");
}

const FIELDS = [["x", 0, 7], ["y", 4, 7], ["z", 8, 7], ["intensity", 12, 7], ["ring", 16, 4],
                ["time", 18, 7]];
const POINT_STEP = 22;

function pointCloud(sec, nanosec, rows, stampS) {
  const data = new Uint8Array(rows.length * POINT_STEP);
  const view = new DataView(data.buffer);
  rows.forEach((r, i) => {
    const at = i * POINT_STEP;
    view.setFloat32(at, r.x, true);
    view.setFloat32(at + 4, r.y, true);
    view.setFloat32(at + 8, r.z, true);
    view.setFloat32(at + 12, r.intensity, true);
    view.setUint16(at + 16, r.ring, true);
    view.setFloat32(at + 18, r.time - stampS, true);
  });
  const cdr = new Cdr();
  cdr.i32(sec);
  cdr.u32(nanosec);
  cdr.string("velodyne");
  cdr.u32(1);
  cdr.u32(rows.length);
  cdr.u32(FIELDS.length);
  for (const [name, offset, datatype] of FIELDS) {
    cdr.string(name);
    cdr.u32(offset);
    cdr.u8(datatype);
    cdr.u32(1);
  }
  cdr.u8(0);  // is_bigendian
  cdr.u32(POINT_STEP);
  cdr.u32(rows.length * POINT_STEP);
  cdr.u32(data.length);
  cdr.bytes(data);
  cdr.u8(1);  // is_dense
  return cdr.message();
}

const CLOUD_SCHEMA = `std_msgs/Header header
uint32 height
uint32 width
PointField[] fields
bool is_bigendian
uint32 point_step
uint32 row_step
uint8[] data
bool is_dense
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
================================================================================
MSG: sensor_msgs/PointField
string name
uint32 offset
uint8 datatype
uint32 count
`;

// The decode CSV's rows by scan, in order.
const lines = (await readFile(csvPath, "utf8")).trim().split("\n");
const header = lines[0].split(",");
const column = (name) => header.indexOf(name);
const scans = new Map();
for (const line of lines.slice(1)) {
  const v = line.split(",");
  const scan = Number(v[column("scan")]);
  if (!scans.has(scan)) scans.set(scan, []);
  scans.get(scan).push({ ring: Number(v[column("ring")]), intensity: Number(v[column("intensity")]),
                         time: Number(v[column("time_s")]), x: Number(v[column("x")]),
                         y: Number(v[column("y")]), z: Number(v[column("z")]) });
}
const hour = hourBase(await readFile(pcapPath));

await zstd.isLoaded;
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
  useChunks: true,
  chunkSize: 1024 * 1024,
  compressChunk: (data) => ({ compression: "zstd", compressedData: zstd.compress(data, 3) }),
});
await writer.start({ profile: "ros2", library: "conicloc test writer (@mcap/core)" });
const schema = await writer.registerSchema({
  name: "sensor_msgs/msg/PointCloud2",
  encoding: "ros2msg",
  data: new TextEncoder().encode(CLOUD_SCHEMA),
});
const channel = await writer.registerChannel({
  topic: "/velodyne_points",
  schemaId: schema,
  messageEncoding: "cdr",
  metadata: new Map(),
});
let sequence = 0;
for (const key of [...scans.keys()].sort((a, b) => a - b)) {
  const rows = scans.get(key).sort((a, b) => a.time - b.time);  // the driver's firing order
  const firstNs = BigInt(hour) * 1000000000n + BigInt(Math.round(rows[0].time * 1e9));
  const sec = Number(firstNs / 1000000000n);
  const nanosec = Number(firstNs % 1000000000n);
  const stampS = sec - hour + nanosec * 1e-9;
  await writer.addMessage({
    channelId: channel,
    sequence: sequence++,
    logTime: firstNs,
    publishTime: firstNs,
    data: pointCloud(sec, nanosec, rows, stampS),
  });
}
await writer.end();
await file.close();
console.log(`${outPath}: ${sequence} clouds`);
