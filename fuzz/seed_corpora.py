#!/usr/bin/env python3
"""Writes the fuzzers' seed corpora, one folder per harness under OUT_DIR.

    fuzz/seed_corpora.py OUT_DIR [--shared DIR]

Always: small synthetic seeds (VLP-16 / HDL-32E data packets in strongest, last and dual mode, a
position packet with a dated GPRMC, the same packets in pcap (µs and ns), pcapng and Linux SLL
captures, TUM and waypoint text). These are what fuzz/corpus/ holds (regenerate with
`fuzz/seed_corpora.py fuzz/corpus`). With --shared (../shared/data): slices of the real Velodyne
captures (first records only) for the packet and capture fuzzers; they stay under the build dir
and are never committed.
"""
import argparse
import pathlib
import struct

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
    for folder, files in ((decoder, seeds), (captures, seeds_capture), (text, seeds_text)):
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
