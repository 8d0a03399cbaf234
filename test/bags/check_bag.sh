#!/usr/bin/env bash
# One bag test for ctest: simulates a short capture, converts it with an independent writer into a
# bag, and checks that conicloc reads the bag exactly like the pcap it was made from.
# Usage: check_bag.sh CONICLOC WORKDIR CASE
#   CASE: rosbag1-none|rosbag1-bz2|rosbag1-lz4, mcap-none|mcap-zstd|mcap-lz4|mcap-unchunked,
#         db3, db3-folder  (decode: the same CSV, byte for byte)
#         localize-rosbag1-bz2, localize-mcap-zstd, localize-db3  (localize: the same poses)
#         mcap-wrong-topic  (--topic naming a topic of another type: a clear error, listing topics)
#         rosbag1-cut, mcap-cut  (a bag cut at 60 %: the points before the cut, the offset named)
#         cloud-rosbag1, cloud-rosbag1-noring, cloud-mcap  (sensor_msgs/PointCloud2 clouds made
#           from the pcap's points, driver style, ROS 1 with and without the ring field, or CDR in
#           MCAP: localize as accurately as the pcap, ATE xy RMSE within 1 cm of each other)
# Exit 77 (ctest's skip) when the writer is not installed.
set -euo pipefail
conicloc=$1
work=$2
case=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work" && cd "$work"

# Debian's python3 holds rosbag; another python3 first on PATH (pyenv, venv) would not.
python=/usr/bin/python3
[ -x "$python" ] || python=python3

"$conicloc" simulate --out run.pcap --truth truth.tum --duration 1.5 --seed 3 > simulate.log 2>&1

write() {  # write FORMAT-MODE OUT
  local status=0
  case $1 in
    rosbag1-*) "$python" "$here/write_rosbag1.py" run.pcap "$2" "${1#rosbag1-}" || status=$? ;;
    mcap-*)
      command -v node > /dev/null || { echo "SKIP: node is not installed"; exit 77; }
      node "$here/write_mcap.mjs" run.pcap "$2" "${1#mcap-}" || status=$? ;;
    db3) python3 "$here/write_db3.py" run.pcap "$2" || status=$? ;;
  esac
  [ $status -eq 77 ] && exit 77
  [ $status -eq 0 ] || { echo "FAIL: the writer exited with $status"; exit 1; }
}

bag_of() {  # the file name of a writer mode
  case $1 in
    rosbag1-*) echo "run.bag" ;;
    mcap-*) echo "run.mcap" ;;
    db3) echo "run.db3" ;;
  esac
}

case $case in
  cloud-rosbag1 | cloud-rosbag1-noring | cloud-mcap)
    "$conicloc" decode run.pcap --csv points.csv > decode_pcap.log 2>&1
    status=0
    case $case in
      cloud-rosbag1) "$python" "$here/write_cloud_rosbag1.py" run.pcap points.csv clouds.bag ||
        status=$? ;;
      cloud-rosbag1-noring)
        "$python" "$here/write_cloud_rosbag1.py" run.pcap points.csv clouds.bag --no-ring ||
          status=$? ;;
      cloud-mcap)
        command -v node > /dev/null || { echo "SKIP: node is not installed"; exit 77; }
        # Named .bag like the others: conicloc recognises a capture by content, not by name.
        node "$here/write_cloud_mcap.mjs" run.pcap points.csv clouds.bag || status=$? ;;
    esac
    [ $status -eq 77 ] && exit 77
    [ $status -eq 0 ] || { echo "FAIL: the writer exited with $status"; exit 1; }
    "$conicloc" decode clouds.bag --csv clouds.csv --stats > decode_bag.log 2>&1 ||
      { cat decode_bag.log; echo "FAIL: the clouds do not decode"; exit 1; }
    grep -q "point_clouds: [1-9]" decode_bag.log || { cat decode_bag.log; exit 1; }
    # Every point comes back (to the CSV's rounding), in its ring.
    [ "$(wc -l < clouds.csv)" -eq "$(wc -l < points.csv)" ] ||
      { echo "FAIL: $(wc -l < clouds.csv) rows from the clouds, $(wc -l < points.csv) from the pcap"
        exit 1; }
    # Row by row (scans, rings, azimuth order): the same scan and ring, the same point within 1 mm.
    paste -d, <(cut -d, -f1,2,7-9 points.csv) <(cut -d, -f1,2,7-9 clouds.csv) |
      awk -F, 'NR > 1 { d = ($3-$8)^2 + ($4-$9)^2 + ($5-$10)^2
                        if ($1 != $6 || $2 != $7 || d > 1e-6) { bad++ } }
               END { if (bad) { print "FAIL: " bad " points differ"; exit 1 } }'
    init=$(awk '!/^#/ {printf "%s,%s,%s,%.4f", $2, $3, $4, atan2(2*($8*$7+$5*$6), 1-2*($6*$6+$7*$7))*57.29577951; exit}' truth.tum)
    options="--init $init --init-sigma 0.3,0.3,20 --threads 1 --seed 5"
    "$conicloc" localize --pcap run.pcap --out pcap.tum $options > localize_pcap.log 2>&1
    "$conicloc" localize --pcap clouds.bag --out bag.tum $options > localize_bag.log 2>&1 ||
      { cat localize_bag.log; echo "FAIL: the clouds do not localize"; exit 1; }
    read -r pcap_ate pcap_poses < <("$python" "$here/ate_xy.py" truth.tum pcap.tum)
    read -r bag_ate bag_poses < <("$python" "$here/ate_xy.py" truth.tum bag.tum)
    echo "ATE xy RMSE: pcap $pcap_ate m over $pcap_poses poses, clouds $bag_ate m over $bag_poses"
    [ "$pcap_poses" -ge 5 ] && [ "$bag_poses" -ge $((pcap_poses - 1)) ] ||
      { echo "FAIL: too few poses"; exit 1; }
    awk -v a="$pcap_ate" -v b="$bag_ate" 'BEGIN { d = a - b; if (d < 0) d = -d
      if (a > 0.15 || b > 0.15 || d > 0.01) exit 1 }' ||
      { echo "FAIL: the clouds localize otherwise than the packets (tolerance 1 cm, both < 15 cm)"
        exit 1; }
    echo "PASS: clouds and packets localize alike"
    ;;
  mcap-wrong-topic)
    write mcap-zstd run.mcap
    if "$conicloc" decode run.mcap --topic /notes > decode.log 2>&1; then
      echo "FAIL: a topic of std_msgs/msg/String was decoded"; exit 1
    fi
    cat decode.log
    grep -q "run.mcap: topics: topic /notes holds std_msgs/msg/String" decode.log
    grep -q "/velodyne_packets  (velodyne_msgs/msg/VelodyneScan, cdr)" decode.log
    echo "PASS: the wrong topic is refused, the topics are listed"
    ;;
  *-cut)
    mode=${case%-cut}-bz2
    [ "${case%-cut}" = mcap ] && mode=mcap-zstd
    bag=$(bag_of "$mode")
    write "$mode" "$bag"
    size=$(stat -c %s "$bag")
    truncate -s $((size * 6 / 10)) "$bag"
    "$conicloc" decode run.pcap --csv pcap.csv > decode_pcap.log 2>&1
    "$conicloc" decode "$bag" --csv bag.csv > decode_bag.log 2>&1 ||
      { cat decode_bag.log; echo "FAIL: a cut bag is not read up to the cut"; exit 1; }
    cat decode_bag.log
    grep -q "$bag: byte offset [0-9]*: cut short or broken; reading stopped after [0-9]* messages" \
      decode_bag.log
    whole=$(wc -l < pcap.csv)
    cut=$(wc -l < bag.csv)
    [ "$cut" -gt $((whole / 3)) ] && [ "$cut" -lt "$whole" ] ||
      { echo "FAIL: $cut of $whole lines from the cut bag"; exit 1; }
    # Every scan before the one the cut ends in is whole: the same lines as from the pcap.
    last_scan=$(tail -1 bag.csv | cut -d, -f1)
    grep -v "^$last_scan," bag.csv > bag_whole.csv
    head -n "$(wc -l < bag_whole.csv)" pcap.csv | cmp - bag_whole.csv
    echo "PASS: $cut of $whole lines before the cut, the offset named"
    ;;
  localize-*)
    mode=${case#localize-}
    bag=$(bag_of "$mode")
    write "$mode" "$bag"
    # Tracking from the true first pose (x,y,z, yaw from the quaternion).
    init=$(awk '!/^#/ {printf "%s,%s,%s,%.4f", $2, $3, $4, atan2(2*($8*$7+$5*$6), 1-2*($6*$6+$7*$7))*57.29577951; exit}' truth.tum)
    options="--init $init --init-sigma 0.3,0.3,20 --threads 1 --seed 5"
    "$conicloc" localize --pcap run.pcap --out pcap.tum $options > localize_pcap.log 2>&1
    "$conicloc" localize --pcap "$bag" --out bag.tum $options > localize_bag.log 2>&1
    poses=$(wc -l < pcap.tum)
    [ "$poses" -ge 5 ] || { echo "FAIL: only $poses poses from the pcap"; exit 1; }
    cmp pcap.tum bag.tum || { echo "FAIL: the bag gives other poses than the pcap"; exit 1; }
    echo "PASS: $poses poses, the same from $bag as from run.pcap"
    ;;
  *)
    mode=$case
    bag=$(bag_of "${mode%-folder}")
    write "${mode%-folder}" "$bag"
    if [ "$mode" = db3-folder ]; then
      mkdir bag_folder && mv "$bag" bag_folder/ && printf 'rosbag2_bagfile_information:\n' \
        > bag_folder/metadata.yaml
      bag=bag_folder
    fi
    "$conicloc" decode run.pcap --csv pcap.csv --stats > decode_pcap.log 2>&1
    "$conicloc" decode "$bag" --csv bag.csv --stats > decode_bag.log 2>&1
    points=$(($(wc -l < pcap.csv) - 1))
    [ "$points" -ge 100000 ] || { echo "FAIL: only $points points from the pcap"; exit 1; }
    cmp pcap.csv bag.csv || { echo "FAIL: $bag decodes to other points than run.pcap"; exit 1; }
    grep "packets_read" decode_bag.log
    echo "PASS: $points points, the same from $bag as from run.pcap"
    ;;
esac
