"""Velodyne data packets of a classic pcap file (Ethernet / IPv4 / UDP), read without conicloc.

Shared by the independent bag writers of the tests: each packet as (sec, nsec, payload), the
stamp being the capture time of its record. Only UDP datagrams to the data port are kept.
"""
import struct

DATA_PORT = 2368
PACKET_BYTES = 1206
PACKETS_PER_SCAN = 76  # one VelodyneScan message per ~rotation of a VLP-16 at 600 rpm


def data_packets(path, port=DATA_PORT):
    with open(path, "rb") as f:
        data = f.read()
    magic = data[:4]
    if magic in (b"\xd4\xc3\xb2\xa1", b"\x4d\x3c\xb2\xa1"):
        endian = "<"
    elif magic in (b"\xa1\xb2\xc3\xd4", b"\xa1\xb2\x3c\x4d"):
        endian = ">"
    else:
        raise ValueError(f"{path}: not a classic pcap file")
    nano = magic in (b"\x4d\x3c\xb2\xa1", b"\xa1\xb2\x3c\x4d")
    link_type = struct.unpack(endian + "I", data[20:24])[0]
    if link_type != 1:
        raise ValueError(f"{path}: link type {link_type}, expected Ethernet")
    offset = 24
    packets = []
    while offset + 16 <= len(data):
        sec, frac, captured, _ = struct.unpack(endian + "IIII", data[offset:offset + 16])
        frame = data[offset + 16:offset + 16 + captured]
        offset += 16 + captured
        if len(frame) < 42 or frame[12:14] != b"\x08\x00" or frame[23] != 17:
            continue
        ihl = (frame[14] & 0x0F) * 4
        udp = frame[14 + ihl:]
        dst_port, length = struct.unpack(">HH", udp[2:6])
        payload = udp[8:length]
        if dst_port == port and len(payload) == PACKET_BYTES:
            packets.append((sec, frac if nano else frac * 1000, payload))
    return packets


def scans(packets):
    """The packets in groups of PACKETS_PER_SCAN, one group per VelodyneScan message."""
    for i in range(0, len(packets), PACKETS_PER_SCAN):
        yield packets[i:i + PACKETS_PER_SCAN]
