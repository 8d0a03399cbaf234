#!/usr/bin/env python3
"""Writes the fuzzers' seed corpora, one folder per harness under OUT_DIR.

    fuzz/seed_corpora.py OUT_DIR [--shared DIR]

Always: small synthetic seeds (VLP-16 / HDL-32E data packets in strongest, last and dual mode, a
position packet with a dated GPRMC, the same packets in pcap (µs and ns), pcapng and Linux SLL
captures, TUM and waypoint text, uncompressed MCAP and ROS 1 bags, a .db3, single VelodyneScan
messages). These are what fuzz/corpus/ holds (regenerate with
`fuzz/seed_corpora.py fuzz/corpus`). With --shared (../shared/data): slices of the real Velodyne
captures (first records only) for the packet and capture fuzzers; they stay under the build dir
and are never committed.
"""
import argparse
import pathlib
import sqlite3
import struct
import tempfile

DATA_PORT, POSITION_PORT = 2368, 8308


def data_packet(first_azimuth, stamp_us, mode=0x37, product=0x22, step=20):
    """A 1206-byte data packet: 12 blocks, ranges that vary by channel, factory bytes."""
    out = bytearray()
    dual = mode == 0x39
    for block in range(12):
        azimuth = (first_azimuth + step * (block // 2 if dual else block)) % 36000
        out += b"\xff\xee" + struct.pack("<H", azimuth)
        for record in range(32):
            distance = 0 if record % 7 == 3 else 1000 + 37 * record + (block % 2) * (3 if dual else 0)
            out += struct.pack("<HB", distance, (record * 9) % 256)
    out += struct.pack("<I", stamp_us) + bytes([mode, product])
    assert len(out) == 1206
    return bytes(out)


def position_packet(stamp_us):
    out = bytearray(512)
    struct.pack_into("<I", out, 198, stamp_us)
    out[202] = 2
    sentence = b"$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A\r\n"
    out[206:206 + len(sentence)] = sentence
    return bytes(out)


def udp_frame(payload, dst_port, sll=False):
    udp = struct.pack(">HHHH", 2368, dst_port, 8 + len(payload), 0) + payload
    ip = struct.pack(">BBHHHBBH4s4s", 0x45, 0, 20 + len(udp), 0, 0x4000, 64, 17, 0,
                     bytes([192, 168, 1, 201]), bytes([255, 255, 255, 255])) + udp
    if sll:
        return struct.pack(">HHH8sH", 0, 1, 6, b"\x60\x76\x88\x00\x00\x00\x00\x00", 0x0800) + ip
    return b"\xff" * 6 + b"\x60\x76\x88\x00\x00\x00" + b"\x08\x00" + ip


def pcap(frames, link=1, nano=False):
    magic = 0xA1B23C4D if nano else 0xA1B2C3D4
    out = struct.pack("<IHHiIII", magic, 2, 4, 0, 0, 65535, link)
    for i, frame in enumerate(frames):
        out += struct.pack("<IIII", 1000 + i // 1000, (i * 553) % 1000, len(frame), len(frame))
        out += frame
    return out


def pcapng(frames):
    def block(kind, body):
        body += b"\x00" * (-len(body) % 4)
        return struct.pack("<II", kind, len(body) + 12) + body + struct.pack("<I", len(body) + 12)

    out = block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    out += block(0x00000001, struct.pack("<HHI", 1, 0, 65535))
    for i, frame in enumerate(frames):
        stamp = 1_000_000_000 + i * 553
        out += block(0x00000006, struct.pack("<IIIII", 0, stamp >> 32, stamp & 0xFFFFFFFF,
                                              len(frame), len(frame)) + frame)
    return out


def ros1_scan(packets):
    """velodyne_msgs/VelodyneScan, ROS 1 serialisation."""
    out = struct.pack("<IIII", 7, 100, 5, 8) + b"velodyne" + struct.pack("<I", len(packets))
    for i, packet in enumerate(packets):
        out += struct.pack("<II", 100, i * 1_000_000) + packet
    return out


def cdr_scan(packets):
    """velodyne_msgs/msg/VelodyneScan, little-endian CDR (4-byte encapsulation header)."""
    out = bytearray(b"\x00\x01\x00\x00") + struct.pack("<III", 100, 5, 9) + b"velodyne\x00"
    while (len(out) - 4) % 4:
        out += b"\x00"
    out += struct.pack("<I", len(packets))
    for i, packet in enumerate(packets):
        while (len(out) - 4) % 4:
            out += b"\x00"
        out += struct.pack("<II", 100, i * 1_000_000) + packet
    return bytes(out)


def mcap_string(text):
    return struct.pack("<I", len(text)) + text


def mcap_record(opcode, content):
    return bytes([opcode]) + struct.pack("<Q", len(content)) + content


def mcap(messages, chunked):
    """An MCAP file: a VelodyneScan channel and a std_msgs/String one, messages at top level or in
    one uncompressed chunk, a footer without a summary."""
    magic = b"\x89MCAP0\r\n"
    header = mcap_record(0x01, mcap_string(b"ros2") + mcap_string(b"seed"))
    records = b""
    for schema, name in ((1, b"velodyne_msgs/msg/VelodyneScan"), (2, b"std_msgs/msg/String")):
        records += mcap_record(0x03, struct.pack("<H", schema) + mcap_string(name) +
                               mcap_string(b"ros2msg") + mcap_string(b""))
    for channel, topic in ((1, b"/velodyne_packets"), (2, b"/notes")):
        records += mcap_record(0x04, struct.pack("<HH", channel, channel) + mcap_string(topic) +
                               mcap_string(b"cdr") + struct.pack("<I", 0))
    for channel, data in messages:
        records += mcap_record(0x05, struct.pack("<HIQQ", channel, 0, 1, 1) + data)
    if chunked:
        records = mcap_record(0x06, struct.pack("<QQQI", 1, 1, len(records), 0) +
                              mcap_string(b"") + struct.pack("<Q", len(records)) + records)
    footer = mcap_record(0x02, struct.pack("<QQI", 0, 0, 0))
    return magic + header + records + footer + magic


def ros1_field(name, value):
    return struct.pack("<I", len(name) + 1 + len(value)) + name + b"=" + value


def ros1_record(header, data):
    return struct.pack("<I", len(header)) + header + struct.pack("<I", len(data)) + data


def ros1_bag(messages, chunked):
    """A ROS 1 bag (format 2.0) without an index: a VelodyneScan and a std_msgs/String connection,
    messages at top level or in one uncompressed chunk."""
    start = b"#ROSBAG V2.0\n" + ros1_record(
        ros1_field(b"op", b"\x03") + ros1_field(b"index_pos", bytes(8)) +
        ros1_field(b"conn_count", struct.pack("<I", 2)) +
        ros1_field(b"chunk_count", struct.pack("<I", 1 if chunked else 0)), b" " * 16)
    records = b""
    for conn, topic, kind in ((0, b"/velodyne_packets", b"velodyne_msgs/VelodyneScan"),
                              (1, b"/notes", b"std_msgs/String")):
        records += ros1_record(
            ros1_field(b"op", b"\x07") + ros1_field(b"conn", struct.pack("<I", conn)) +
            ros1_field(b"topic", topic),
            ros1_field(b"topic", topic) + ros1_field(b"type", kind) + ros1_field(b"md5sum", b"*"))
    for conn, data in messages:
        records += ros1_record(
            ros1_field(b"op", b"\x02") + ros1_field(b"conn", struct.pack("<I", conn)) +
            ros1_field(b"time", struct.pack("<II", 100, 0)), data)
    if chunked:
        records = ros1_record(
            ros1_field(b"op", b"\x05") + ros1_field(b"compression", b"none") +
            ros1_field(b"size", struct.pack("<I", len(records))), records)
    return start + records


def db3(messages):
    """A ROS 2 sqlite3 bag (.db3): the topics and messages tables as rosbag2 writes them."""
    with tempfile.TemporaryDirectory() as folder:
        path = pathlib.Path(folder) / "seed.db3"
        db = sqlite3.connect(path)
        db.execute("PRAGMA page_size = 512")
        db.execute("CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT "
                   "NULL, serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL)")
        db.execute("CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, "
                   "timestamp INTEGER NOT NULL, data BLOB NOT NULL)")
        db.execute("INSERT INTO topics VALUES (1, '/velodyne_packets', "
                   "'velodyne_msgs/msg/VelodyneScan', 'cdr', '')")
        db.execute("INSERT INTO topics VALUES (2, '/notes', 'std_msgs/msg/String', 'cdr', '')")
        for i, (topic, data) in enumerate(messages):
            db.execute("INSERT INTO messages VALUES (?, ?, ?, ?)", (i + 1, topic, i, data))
        db.commit()
        db.close()
        return path.read_bytes()


def bag_seeds():
    """Uncompressed bags and single messages for the bag reader and message fuzzers."""
    packets = [data_packet(100 + 40 * i, 1_000_000 + 1327 * i) for i in range(2)]
    note = b"\x00\x01\x00\x00" + struct.pack("<I", 3) + b"hi\x00"
    return {
        "fuzz_mcap_reader": {
            "vlp16.mcap": mcap([(1, cdr_scan(packets[:1])), (2, note)], chunked=False),
            "vlp16_chunked.mcap": mcap([(1, cdr_scan(packets[1:])), (2, note)], chunked=True),
        },
        "fuzz_rosbag1_reader": {
            "vlp16.bag": ros1_bag([(0, ros1_scan(packets[:1])), (1, struct.pack("<I", 2) + b"hi")],
                                  chunked=False),
            "vlp16_chunked.bag": ros1_bag([(0, ros1_scan(packets[1:]))], chunked=True),
        },
        "fuzz_ros2_db3_reader": {
            "vlp16.db3": db3([(1, cdr_scan(packets[:1])), (2, note)]),
        },
        "fuzz_velodyne_scan_msg": {
            # Control byte: even ROS 1, odd CDR (fuzz/bag_reader_input.hpp).
            "ros1_two_packets": b"\x00" + ros1_scan(packets),
            "cdr_one_packet": b"\x01" + cdr_scan(packets[:1]),
            "cdr_empty": b"\x01" + cdr_scan([]),
        },
    }


def synthetic(out):
    decoder = out / "fuzz_velodyne_decoder"
    # Control byte: bits 0-2 model (0 VLP-16, 3 HDL-32E), see fuzz/fuzz_velodyne_decoder.cpp.
    seeds = {
        "vlp16_strongest": bytes([0]) + data_packet(100, 1_000_000),
        "vlp16_last": bytes([0]) + data_packet(35900, 2_000_000, mode=0x38),
        "vlp16_dual": bytes([0]) + data_packet(17990, 3_000_000, mode=0x39),
        "hdl32_strongest": bytes([3]) + data_packet(500, 4_000_000, product=0x21, step=16),
        "vlp32c_strongest": bytes([4]) + data_packet(500, 4_000_000, product=0x28, step=8),
        "position": bytes([0]) + position_packet(1_234_567),
    }
    captures = out / "fuzz_capture_reader"
    frames = [udp_frame(data_packet(35960 - 0 + 40 * i, 3_599_999_000 + 1327 * i), DATA_PORT)
              for i in range(2)]
    frames.insert(1, udp_frame(position_packet(3_599_999_500), POSITION_PORT))
    seeds_capture = {
        "vlp16_hour_wrap.pcap": pcap(frames),
        "vlp16_nano.pcap": pcap(frames[:2], nano=True),
        "vlp16.pcapng": pcapng(frames),
        "vlp16_sll.pcap": pcap([udp_frame(data_packet(0, 10), DATA_PORT, sll=True)], link=113),
    }
    text = out / "fuzz_trajectory_text"
    seeds_text = {
        "tum": b"\x00# t tx ty tz qx qy qz qw\n0.0 1 2 0 0 0 0 1\n0.1 1.1 2 0 0 0 0.0998 0.995\n",
        "waypoints": b"\x01# x y [z] [yaw_deg]\n0 0\n4.5 0 0\n4.5 3 0 90\n",
    }
    folders = [(decoder, seeds), (captures, seeds_capture), (text, seeds_text)]
    folders += [(out / target, files) for target, files in bag_seeds().items()]
    for folder, files in folders:
        folder.mkdir(parents=True, exist_ok=True)
        for name, content in files.items():
            (folder / name).write_bytes(content)


def shared_slices(out, shared):
    """The first records of each real capture (as a smaller capture) and their payloads."""
    for path in sorted((shared / "velodyne").glob("*.pcap")):
        raw = path.read_bytes()
        header, offset, records = raw[:24], 24, []
        while offset + 16 <= len(raw) and len(records) < 24:
            captured = struct.unpack_from("<I", raw, offset + 8)[0]
            records.append(raw[offset:offset + 16 + captured])
            offset += 16 + captured
        (out / "fuzz_capture_reader").mkdir(parents=True, exist_ok=True)
        (out / "fuzz_capture_reader" / (path.stem + "_head.pcap")).write_bytes(
            header + b"".join(records[:6]))
        decoder = out / "fuzz_velodyne_decoder"
        decoder.mkdir(parents=True, exist_ok=True)
        data_seen = position_seen = 0
        for i, record in enumerate(records):
            payload = record[16 + 42:]
            if len(payload) == 1206 and data_seen < 3:
                data_seen += 1
                model = 3 if "monterey" in path.stem else 0
                (decoder / f"{path.stem}_{i}").write_bytes(bytes([model]) + payload)
            elif len(payload) == 512 and position_seen < 1:
                position_seen += 1
                (decoder / f"{path.stem}_{i}_position").write_bytes(bytes([0]) + payload)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", type=pathlib.Path)
    parser.add_argument("--shared", type=pathlib.Path, help="../shared/data (optional)")
    args = parser.parse_args()
    synthetic(args.out_dir)
    if args.shared and (args.shared / "velodyne").is_dir():
        shared_slices(args.out_dir, args.shared)


if __name__ == "__main__":
    main()
