#!/usr/bin/python3
"""Writes a ROS 1 bag of velodyne_msgs/VelodyneScan from a pcap with Debian's python3-rosbag.

Usage: write_rosbag1.py PCAP OUT.bag none|bz2|lz4 [TOPIC]
Exit 77 (a skip for ctest) when rosbag (or roslz4 for lz4) is not installed. The message classes
are generated at run time from the message definitions (genpy), so no ROS workspace is needed.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pcap_packets  # noqa: E402

SCAN_DEFINITION = """std_msgs/Header header
velodyne_msgs/VelodynePacket[] packets
================================================================================
MSG: std_msgs/Header
uint32 seq
time stamp
string frame_id
================================================================================
MSG: velodyne_msgs/VelodynePacket
time stamp
uint8[1206] data
"""


def main():
    pcap, out, compression = sys.argv[1:4]
    topic = sys.argv[4] if len(sys.argv) > 4 else "/velodyne_packets"
    try:
        import genpy
        import genpy.dynamic
        import rosbag
        if compression == "lz4":
            import roslz4  # noqa: F401
    except ImportError as e:
        print(f"SKIP: the ROS 1 bag writer is not installed ({e}); apt-get install python3-rosbag "
              "python3-roslz4")
        return 77
    classes = genpy.dynamic.generate_dynamic("velodyne_msgs/VelodyneScan", SCAN_DEFINITION)
    Scan = classes["velodyne_msgs/VelodyneScan"]
    Packet = classes["velodyne_msgs/VelodynePacket"]
    packets = pcap_packets.data_packets(pcap)
    with rosbag.Bag(out, "w", compression=compression, chunk_threshold=256 * 1024) as bag:
        for seq, group in enumerate(pcap_packets.scans(packets)):
            scan = Scan()
            scan.header.seq = seq
            scan.header.stamp = genpy.Time(group[-1][0], group[-1][1])
            scan.header.frame_id = "velodyne"
            scan.packets = [Packet(stamp=genpy.Time(s, ns), data=payload) for s, ns, payload in group]
            bag.write(topic, scan, scan.header.stamp)
    print(f"{out}: {len(packets)} packets, {compression} chunks")
    return 0


if __name__ == "__main__":
    sys.exit(main())
