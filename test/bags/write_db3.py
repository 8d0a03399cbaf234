#!/usr/bin/env python3
"""Writes a ROS 2 bag in rosbag2's sqlite3 storage (.db3) of velodyne_msgs/msg/VelodyneScan.

Usage: write_db3.py PCAP OUT.db3 [TOPIC]
The schema is rosbag2's (topics, messages, metadata.yaml beside the file for a bag folder); the
messages are CDR, encoded here by hand from the ROS 2 message definitions, independent of
conicloc's reader. Python's standard library only.
"""
import os
import sqlite3
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pcap_packets  # noqa: E402


class CdrWriter:
    """Plain little-endian CDR: each primitive aligned to its size from the end of the 4-byte
    encapsulation header; strings carry their NUL in the length."""

    def __init__(self):
        self.body = bytearray()

    def align(self, size):
        self.body += b"\0" * (-len(self.body) % size)

    def u32(self, value):
        self.align(4)
        self.body += struct.pack("<I", value)

    def i32(self, value):
        self.align(4)
        self.body += struct.pack("<i", value)

    def string(self, text):
        data = text.encode() + b"\0"
        self.u32(len(data))
        self.body += data

    def message(self):
        return b"\x00\x01\x00\x00" + bytes(self.body)


def velodyne_scan_cdr(group, frame_id="velodyne"):
    cdr = CdrWriter()
    cdr.i32(group[-1][0])  # header.stamp.sec
    cdr.u32(group[-1][1])  # header.stamp.nanosec
    cdr.string(frame_id)
    cdr.u32(len(group))  # sequence<VelodynePacket>
    for sec, nsec, payload in group:
        cdr.i32(sec)
        cdr.u32(nsec)
        cdr.body += payload  # uint8[1206]: fixed size, no length
    return cdr.message()


SCHEMA = """
CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);
CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL,
                      metadata TEXT NOT NULL);
CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,
                    serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL,
                    type_description_hash TEXT NOT NULL);
CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL,
                      timestamp INTEGER NOT NULL, data BLOB NOT NULL);
CREATE INDEX timestamp_idx ON messages (timestamp ASC);
"""


def main():
    pcap, out = sys.argv[1:3]
    topic = sys.argv[3] if len(sys.argv) > 3 else "/velodyne_packets"
    packets = pcap_packets.data_packets(pcap)
    if os.path.exists(out):
        os.remove(out)
    db = sqlite3.connect(out)
    db.executescript(SCHEMA)
    db.execute("INSERT INTO schema VALUES (3, 'jazzy')")
    db.execute("INSERT INTO topics VALUES (1, '/diagnostics', 'diagnostic_msgs/msg/DiagnosticArray',"
               " 'cdr', '', '')")
    db.execute("INSERT INTO topics VALUES (2, ?, 'velodyne_msgs/msg/VelodyneScan', 'cdr', '', '')",
               (topic,))
    for group in pcap_packets.scans(packets):
        stamp_ns = group[-1][0] * 1_000_000_000 + group[-1][1]
        db.execute("INSERT INTO messages (topic_id, timestamp, data) VALUES (2, ?, ?)",
                   (stamp_ns, velodyne_scan_cdr(group)))
    db.commit()
    db.close()
    print(f"{out}: {len(packets)} packets")
    return 0


if __name__ == "__main__":
    sys.exit(main())
