#!/usr/bin/python3
"""Writes a ROS 1 bag of sensor_msgs/PointCloud2, one cloud per rotation, as the ROS Velodyne
driver (velodyne_pointcloud, PointXYZIRT) publishes them, with Debian's python3-rosbag.

Usage: write_cloud_rosbag1.py PCAP POINTS.csv OUT.bag [--no-ring]
POINTS.csv is `conicloc decode PCAP --csv` (scan,ring,azimuth_deg,range_m,intensity,time_s,x,y,z,
return; time_s on the device clock, seconds past the hour). The device clock is put on UTC with
the hour of the pcap's first data packet (its capture time less its µs-past-the-hour stamp). Each
cloud is stamped with its first firing; its field `time` is seconds after that stamp. Fields:
x y z intensity (float32), ring (uint16), time (float32), packed one after the other as the
driver's PointCloud2 modifier lays them out (22 bytes, time unaligned at 18); with --no-ring the
ring field is left out (its bytes stay). Exit 77 (a skip for ctest) without rosbag.
"""
import csv
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pcap_packets  # noqa: E402

CLOUD_DEFINITION = """std_msgs/Header header
uint32 height
uint32 width
sensor_msgs/PointField[] fields
bool is_bigendian
uint32 point_step
uint32 row_step
uint8[] data
bool is_dense
================================================================================
MSG: std_msgs/Header
uint32 seq
time stamp
string frame_id
================================================================================
MSG: sensor_msgs/PointField
uint8 INT8=1
uint8 UINT8=2
uint8 INT16=3
uint8 UINT16=4
uint8 INT32=5
uint8 UINT32=6
uint8 FLOAT32=7
uint8 FLOAT64=8
string name
uint32 offset
uint8 datatype
uint32 count
"""


def hour_base_s(pcap):
    """UTC of the device clock's hour: capture time of the first packet less its stamp."""
    sec, nsec, payload = pcap_packets.data_packets(pcap)[0]
    stamp_us = struct.unpack("<I", payload[1200:1204])[0]
    return round((sec + nsec * 1e-9 - stamp_us * 1e-6) / 3600.0) * 3600


def rotations(points_csv):
    """The rows of the decode CSV grouped by scan, in order."""
    scans = {}
    with open(points_csv, newline="") as f:
        for row in csv.DictReader(f):
            scans.setdefault(int(row["scan"]), []).append(row)
    return [scans[k] for k in sorted(scans)]


def main():
    pcap, points_csv, out = sys.argv[1:4]
    with_ring = "--no-ring" not in sys.argv[4:]
    try:
        import genpy
        import genpy.dynamic
        import rosbag
    except ImportError as e:
        print(f"SKIP: the ROS 1 bag writer is not installed ({e}); apt-get install python3-rosbag")
        return 77
    classes = genpy.dynamic.generate_dynamic("sensor_msgs/PointCloud2", CLOUD_DEFINITION)
    Cloud = classes["sensor_msgs/PointCloud2"]
    Field = classes["sensor_msgs/PointField"]
    layout = [("x", 0, 7), ("y", 4, 7), ("z", 8, 7), ("intensity", 12, 7)]
    layout += [("ring", 16, 4)] if with_ring else []
    layout += [("time", 18, 7)]
    point_step = 22
    hour = hour_base_s(pcap)
    clouds = 0
    with rosbag.Bag(out, "w", compression="none") as bag:
        for seq, rows in enumerate(rotations(points_csv)):
            # The driver orders a cloud by firing; its stamp is the first firing's time.
            rows.sort(key=lambda r: float(r["time_s"]))
            first_s = float(rows[0]["time_s"])
            stamp = genpy.Time.from_sec(hour + first_s)
            stamp_s = stamp.to_sec() - hour
            data = bytearray(point_step * len(rows))
            for i, r in enumerate(rows):
                struct.pack_into("<ffffHf", data, i * point_step, float(r["x"]), float(r["y"]),
                                 float(r["z"]), float(r["intensity"]),
                                 int(r["ring"]) if with_ring else 0, float(r["time_s"]) - stamp_s)
            cloud = Cloud()
            cloud.header.seq = seq
            cloud.header.stamp = stamp
            cloud.header.frame_id = "velodyne"
            cloud.height = 1
            cloud.width = len(rows)
            cloud.fields = [Field(name=n, offset=o, datatype=t, count=1) for n, o, t in layout]
            cloud.is_bigendian = False
            cloud.point_step = point_step
            cloud.row_step = point_step * len(rows)
            cloud.data = bytes(data)
            cloud.is_dense = True
            bag.write("/velodyne_points", cloud, stamp)
            clouds += 1
    print(f"{out}: {clouds} clouds{'' if with_ring else ' without ring'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
