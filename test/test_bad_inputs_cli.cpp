// Bad input through the real `conicloc` binary, one case per test: every sub-command that reads a
// file is given broken captures, models, trajectories and waypoints. Each must end with a chosen
// exit status (never a signal, never the time limit) and a message naming the file and the place;
// a damaged capture must still yield every good packet, compared point by point with the decode
// of the clean capture the simulator wrote.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "test/capture_bytes.hpp"
#include "test/cli_guarded_run.hpp"
#include "test/temp_path.hpp"

namespace conicloc::test {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kTimestampOffset = 1200;  // in the 1206-byte data payload
constexpr int kDataPort = 2368;

std::string quoted(const fs::path& path) {
  return "'" + path.string() + "'";
}

std::string indoorgml_file(const std::string& name) {
  return std::string(CONICLOC_TEST_DATA) + "/indoorgml/" + name;
}

std::string read_file(const std::string& path) {
  return file_text(path);
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("template lacks " + from);
  return text.replace(at, from.size(), to);
}

// "key: value" from `conicloc decode --stats`.
std::string stat(const std::string& out, const std::string& key) {
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    const auto first = line.find_first_not_of(' ');
    if (first != std::string::npos && line.compare(first, key.size() + 2, key + ": ") == 0)
      return line.substr(first + key.size() + 2);
  }
  return "<no " + key + ">";
}

// Decoded returns keyed by firing time (µs): each row of the CSV without its scan index (which
// counts rotations and so depends on what came before).
using Rows = std::multimap<long long, std::string>;

Rows read_rows(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  Rows rows;
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::istringstream split(line);
    for (std::string f; std::getline(split, f, ',');) fields.push_back(f);
    if (fields.size() != 10) throw std::runtime_error("bad CSV row: " + line);
    const long long time_us = std::llround(std::stod(fields[5]) * 1e6);
    rows.emplace(time_us, line.substr(line.find(',') + 1));
  }
  return rows;
}

std::uint32_t packet_stamp_us(const PcapRecord& record) {
  return le32(record.frame.data() + kUdpPayloadOffset + kTimestampOffset);
}

// The clean rows minus those of the data packets at `dropped` (indices into `records`): a packet's
// firings lie between its time stamp and the next packet's.
Rows expected_rows(const Rows& clean, const std::vector<PcapRecord>& records,
                   const std::vector<std::size_t>& dropped) {
  Rows expected = clean;
  for (const std::size_t index : dropped) {
    const long long begin = packet_stamp_us(records[index]);
    const long long end = index + 1 < records.size()
                              ? static_cast<long long>(packet_stamp_us(records[index + 1]))
                              : begin + 100000;
    expected.erase(expected.lower_bound(begin), expected.lower_bound(end));
  }
  return expected;
}

::testing::AssertionResult same_rows(const Rows& expected, const Rows& actual) {
  if (expected.size() != actual.size()) {
    return ::testing::AssertionFailure()
           << expected.size() << " rows expected, " << actual.size() << " decoded";
  }
  auto a = actual.begin();
  for (auto e = expected.begin(); e != expected.end(); ++e, ++a) {
    if (e->first != a->first || e->second != a->second) {
      return ::testing::AssertionFailure() << "expected " << e->second << ", decoded " << a->second;
    }
  }
  return ::testing::AssertionSuccess();
}

class BadInputCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = unique_temp_path(std::string("badcli_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path path(const std::string& name) const { return dir_ / name; }
  GuardedRun run(const std::string& arguments) { return run_guarded(dir_, arguments); }

  // A clean 0.5 s VLP-16 capture of the example building (exact ranges) and its decoded rows.
  void make_clean_capture(const std::string& extra = "") {
    const auto sim = run("simulate --out " + quoted(path("clean.pcap")) + " --truth " +
                         quoted(path("truth.tum")) + " --duration 0.5 --no-effects --seed 7 " +
                         "--threads 1 " + extra);
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    clean_ = PcapFile::parse(read_bytes(path("clean.pcap")));
    ASSERT_GT(clean_.records.size(), 300u);
    const auto decoded = decode(path("clean.pcap"), "clean.csv");
    ASSERT_EQ(decoded.exit_code, 0) << decoded.err;
    clean_rows_ = read_rows(path("clean.csv"));
    ASSERT_GT(clean_rows_.size(), 100000u);
  }

  GuardedRun decode(const fs::path& capture, const std::string& csv_name) {
    return run("decode --stats --model vlp16 " + quoted(capture) + " --csv " +
               quoted(path(csv_name)));
  }

  // Exit status `code` with a message on stderr holding every one of `parts`.
  void expect_error(const GuardedRun& result, int code, const std::vector<std::string>& parts) {
    ASSERT_TRUE(result.clean_exit()) << "crashed or hung; stderr:\n" << result.err;
    EXPECT_EQ(result.exit_code, code) << result.err;
    for (const auto& part : parts)
      EXPECT_NE(result.err.find(part), std::string::npos) << "missing \"" << part << "\" in:\n"
                                                          << result.err;
  }

  fs::path dir_;
  PcapFile clean_;
  Rows clean_rows_;
};

// ---------------------------------------------------------------------------------------------
// Captures (decode)

TEST_F(BadInputCli, DecodeCorruptedPacketsAreRejectedAndEveryGoodOneDecoded) {
  make_clean_capture();
  PcapFile bad = clean_;
  std::mt19937 rng(3);
  auto payload = [&](std::size_t record) {
    return bad.records[record].frame.data() + kUdpPayloadOffset;
  };
  payload(10)[100] = 0x00;  // block 1's 0xFFEE flag
  for (int i = 150; i < 350; ++i) payload(100)[i] = static_cast<std::uint8_t>(rng());  // noise
  payload(200)[2] = 0xFF;  // block 0 azimuth 65535
  payload(200)[3] = 0xFF;
  std::fill(payload(300), payload(300) + 1206, std::uint8_t{0});  // a blank packet
  write_bytes(path("bad.pcap"), bad.serialize());

  const auto result = decode(path("bad.pcap"), "bad.csv");
  expect_error(result, 0,
               {"bad.pcap: record 11: data packet rejected (bad_block_flag)",
                "bad.pcap: record 101: data packet rejected (bad_block_flag)",
                "bad.pcap: record 201: data packet rejected (azimuth_out_of_range)",
                "bad.pcap: record 301: data packet rejected (all_zero)"});
  EXPECT_EQ(stat(result.out, "rejected_packets"), "4");
  EXPECT_EQ(stat(result.out, "data_packets"), std::to_string(clean_.records.size() - 4));
  EXPECT_TRUE(same_rows(expected_rows(clean_rows_, clean_.records, {10, 100, 200, 300}),
                        read_rows(path("bad.csv"))));

  // localize goes on past the same packets and names them the same way.
  const auto located = run("localize --pcap " + quoted(path("bad.pcap")) + " --out " +
                           quoted(path("bad.tum")) + " --init 9,2,0.8,92 --particles 50 " +
                           "--init-particles 50 --threads 1");
  expect_error(located, 0,
               {"bad.pcap: record 11: data packet rejected (bad_block_flag)",
                "bad.pcap: record 301: data packet rejected (all_zero)", "4 rejected"});
}

TEST_F(BadInputCli, DecodeCaptureCutMidRecordKeepsEveryCompleteRecord) {
  make_clean_capture();  // the full-disk case: the writer stopped inside record 201
  const std::size_t kept = 200;
  const std::size_t cut_at = clean_.record_offset(kept) + 600;
  Bytes bytes = clean_.serialize();
  bytes.resize(cut_at);
  write_bytes(path("cut.pcap"), bytes);

  const auto result = decode(path("cut.pcap"), "cut.csv");
  expect_error(result, 0,
               {"cut.pcap: record 201 at byte offset " + std::to_string(clean_.record_offset(kept)),
                "after 200 complete records"});
  EXPECT_EQ(stat(result.out, "data_packets"), "200");
  EXPECT_EQ(stat(result.out, "truncated_records"), "1");
  std::vector<std::size_t> lost;
  for (std::size_t i = kept; i < clean_.records.size(); ++i) lost.push_back(i);
  EXPECT_TRUE(
      same_rows(expected_rows(clean_rows_, clean_.records, lost), read_rows(path("cut.csv"))));
}

TEST_F(BadInputCli, DecodeBrokenRecordHeaderStopsThereKeepingEveryRecordBefore) {
  make_clean_capture();  // a record claims 2 GB: libpcap cannot resynchronise after it
  const std::size_t broken = 150;
  const std::size_t offset = clean_.record_offset(broken);
  Bytes bytes = clean_.serialize();
  for (std::size_t i : {8, 12}) {
    bytes[offset + i + 3] = 0x7F;
    bytes[offset + i + 2] = 0xFF;
  }
  write_bytes(path("broken.pcap"), bytes);

  const auto result = decode(path("broken.pcap"), "broken.csv");
  expect_error(result, 0, {"broken.pcap: record 151 at byte offset " + std::to_string(offset)});
  EXPECT_EQ(stat(result.out, "data_packets"), "150");
  std::vector<std::size_t> lost;
  for (std::size_t i = broken; i < clean_.records.size(); ++i) lost.push_back(i);
  EXPECT_TRUE(
      same_rows(expected_rows(clean_rows_, clean_.records, lost), read_rows(path("broken.csv"))));
}

TEST_F(BadInputCli, DecodeCaptureCutInsideTheFileHeaderIsAnError) {
  make_clean_capture();
  Bytes bytes = clean_.serialize();
  bytes.resize(10);
  write_bytes(path("stub.pcap"), bytes);
  expect_error(decode(path("stub.pcap"), "stub.csv"), 1,
               {"stub.pcap: file header: not a readable pcap/pcapng capture"});
}

TEST_F(BadInputCli, DecodeBadMagicIsAnError) {
  make_clean_capture();
  Bytes bytes = clean_.serialize();
  std::fill(bytes.begin(), bytes.begin() + 4, std::uint8_t{0x42});
  write_bytes(path("magic.pcap"), bytes);
  expect_error(decode(path("magic.pcap"), "magic.csv"), 1,
               {"magic.pcap: file header: not a readable pcap/pcapng capture"});
}

TEST_F(BadInputCli, DecodeForeignTrafficIsSkippedAndEveryDataPacketDecoded) {
  make_clean_capture();
  PcapFile mixed = clean_;
  mixed.records.clear();
  const Bytes small(100, 0xAB), wrong_size(512, 0xFF), tcp(40, 0x11);
  Bytes arp(12, 0x02);
  arp.insert(arp.end(), {0x08, 0x06});
  arp.resize(60, 0);
  Bytes ipv6(12, 0x02);
  ipv6.insert(ipv6.end(), {0x86, 0xDD, 0x60});
  ipv6.resize(90, 0);
  Bytes bad_udp_length = ipv4_frame(17, kDataPort, small);
  bad_udp_length[14 + 20 + 4] = 0x40;  // UDP length 16k, beyond the frame
  std::size_t foreign = 0, wrong = 0, other = 0, malformed = 0;
  for (std::size_t i = 0; i < clean_.records.size(); ++i) {
    mixed.records.push_back(clean_.records[i]);
    if (i % 50 != 7) continue;
    PcapRecord extra = clean_.records[i];
    for (const auto& frame : {ipv4_frame(17, 53, small), ipv4_frame(17, 9000, Bytes(1206, 0xFF))}) {
      extra.frame = frame;
      mixed.records.push_back(extra);
      ++foreign;
    }
    extra.frame = ipv4_frame(17, kDataPort, wrong_size);
    mixed.records.push_back(extra);
    ++wrong;
    for (const auto& frame :
         {arp, ipv6, ipv4_frame(6, 0, tcp), ipv4_frame(17, kDataPort, small, 0x2000)}) {
      extra.frame = frame;  // ARP, IPv6, TCP, a first IP fragment
      mixed.records.push_back(extra);
      ++other;
    }
    extra.frame = bad_udp_length;
    mixed.records.push_back(extra);
    ++malformed;
  }
  write_bytes(path("mixed.pcap"), mixed.serialize());

  const auto result = decode(path("mixed.pcap"), "mixed.csv");
  expect_error(result, 0, {"mixed.pcap: record 11: data packet rejected (wrong_size)"});
  EXPECT_EQ(stat(result.out, "data_packets"), std::to_string(clean_.records.size()));
  EXPECT_EQ(stat(result.out, "rejected_wrong_size"), std::to_string(wrong));
  EXPECT_EQ(stat(result.out, "foreign_port"), std::to_string(foreign));
  EXPECT_EQ(stat(result.out, "not_ipv4_udp"), std::to_string(other));
  EXPECT_EQ(stat(result.out, "malformed_ip_udp"), std::to_string(malformed));
  EXPECT_EQ(stat(result.out, "packets_lost_estimate"), "0");
  EXPECT_TRUE(same_rows(clean_rows_, read_rows(path("mixed.csv"))));
}

TEST_F(BadInputCli, DecodeDeviceClockWrappingTheHourLosesNothing) {
  // First firing 0.3 s before the UTC hour: the device clock (µs past the hour) wraps to 0.
  make_clean_capture("--start-epoch 1767225599.7");
  EXPECT_GT(packet_stamp_us(clean_.records.front()), 3599000000u);
  EXPECT_LT(packet_stamp_us(clean_.records.back()), 1000000u);
  const auto result = decode(path("clean.pcap"), "again.csv");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(stat(result.out, "clock_wraps"), "1");
  EXPECT_EQ(stat(result.out, "rejected_packets"), "0");
  EXPECT_EQ(stat(result.out, "packets_lost_estimate"), "0");
  EXPECT_EQ(stat(result.out, "data_packets"), std::to_string(clean_.records.size()));
  // Times run on through the hour: 0.5 s of firings, no jump back by an hour.
  ASSERT_FALSE(clean_rows_.empty());
  const double span_s = (clean_rows_.rbegin()->first - clean_rows_.begin()->first) * 1e-6;
  EXPECT_GT(span_s, 0.45);
  EXPECT_LT(span_s, 0.51);
}

TEST_F(BadInputCli, DecodePcapngWithUnknownBlocksDecodesEveryPacket) {
  make_clean_capture();
  Bytes unknown;  // block type 0x0BAD, 8 bytes of body
  put_le32(unknown, 0x00000BAD);
  put_le32(unknown, 20);
  for (int i = 0; i < 8; ++i) unknown.push_back(static_cast<std::uint8_t>(0xC0 + i));
  put_le32(unknown, 20);
  write_bytes(path("blocks.pcapng"), to_pcapng(clean_, 25, unknown));
  const auto result = decode(path("blocks.pcapng"), "blocks.csv");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(stat(result.out, "data_packets"), std::to_string(clean_.records.size()));
  EXPECT_EQ(stat(result.out, "rejected_packets"), "0");
  EXPECT_TRUE(same_rows(clean_rows_, read_rows(path("blocks.csv"))));
}

TEST_F(BadInputCli, DecodePcapngCutMidBlockKeepsEveryCompleteBlock) {
  make_clean_capture();
  Bytes bytes = to_pcapng(clean_, 0, {});
  bytes.resize(bytes.size() - 700);  // inside the last enhanced packet block
  write_bytes(path("cut.pcapng"), bytes);
  const auto result = decode(path("cut.pcapng"), "cut.csv");
  expect_error(result, 0, {"cut.pcapng: record " + std::to_string(clean_.records.size())});
  EXPECT_EQ(stat(result.out, "data_packets"), std::to_string(clean_.records.size() - 1));
  EXPECT_TRUE(same_rows(expected_rows(clean_rows_, clean_.records, {clean_.records.size() - 1}),
                        read_rows(path("cut.csv"))));
}

TEST_F(BadInputCli, DecodeMissingDirectoryAndEmptyFiles) {
  expect_error(decode(path("absent.pcap"), "a.csv"), 1,
               {"absent.pcap: file header", "No such file"});
  expect_error(decode(dir_, "b.csv"), 1, {dir_.string() + ": file header", "directory"});
  write_file(path("empty.pcap"), "");
  expect_error(decode(path("empty.pcap"), "c.csv"), 1, {"empty.pcap: file header"});
}

TEST_F(BadInputCli, DecodeBadCalibrationFileIsAnError) {
  make_clean_capture();
  write_file(path("calib.xml"), "<boost_serialization><DB><points_><count>16</count>");
  expect_error(
      run("decode " + quoted(path("clean.pcap")) + " --calibration " + quoted(path("calib.xml"))),
      1, {"calib.xml: byte offset", "cannot read calibration XML"});
}

// ---------------------------------------------------------------------------------------------
// IndoorGML models (map-info, map-export, predict, simulate, localize)

// Every number inside <gml:pos> and <gml:posList> moved by `offset_m`.
std::string shifted_coordinates(const std::string& text, double offset_m) {
  std::string out;
  std::size_t at = 0;
  for (;;) {
    const auto open = text.find("<gml:pos", at);
    const auto begin = open == std::string::npos ? open : text.find('>', open);
    if (begin == std::string::npos) break;
    const auto end = text.find('<', begin);
    out += text.substr(at, begin + 1 - at);
    std::istringstream numbers(text.substr(begin + 1, end - begin - 1));
    for (double v; numbers >> v;) out += std::to_string(v + offset_m) + " ";
    at = end;
  }
  return out + text.substr(at);
}

class BadGml : public BadInputCli {
 protected:
  // v101_room.gml with one coordinate replaced; line 10 is the R1-ceil polygon's second pos.
  std::string room_with(const std::string& coordinate) {
    return replace_once(read_file(indoorgml_file("v101_room.gml")),
                        "<gml:pos>4.0 0.0 2.5</gml:pos>", "<gml:pos>" + coordinate + "</gml:pos>");
  }
  GuardedRun map_info(const fs::path& file) { return run("map-info " + quoted(file)); }
};

TEST_F(BadGml, BrokenXlinkNamesElementIdAndLine) {
  write_file(path("xlink.gml"), replace_once(read_file(indoorgml_file("v103_two_rooms_door.gml")),
                                             "xlink:href=\"#B-floor\"", "xlink:href=\"#NOPE\""));
  expect_error(map_info(path("xlink.gml")), 1,
               {"xlink.gml: line 121", "element surfaceMember", "#NOPE"});
}

TEST_F(BadGml, NanAndInfCoordinatesNameElementIdAndLine) {
  for (const char* value : {"4.0 NaN 2.5", "4.0 inf 2.5", "-Infinity 0 2.5", "4.0 0.0 1e400"}) {
    write_file(path("nan.gml"), room_with(value));
    expect_error(map_info(path("nan.gml")), 1,
                 {"nan.gml: line 10, element pos in Polygon (gml:id=\"R1-ceil\")"});
  }
}

TEST_F(BadGml, HugeCoordinateIsOutOfRange) {
  write_file(path("huge.gml"), room_with("4.0 1e300 2.5"));
  expect_error(
      map_info(path("huge.gml")), 1,
      {"huge.gml: line 10, element pos in Polygon (gml:id=\"R1-ceil\")", "1e300", "out of range"});
}

TEST_F(BadGml, LargeOffsetMovesToTheOrigin) {
  // Every coordinate 1e7 m out (a projected CRS): loads, with the offset moved to the origin.
  write_file(path("far.gml"), shifted_coordinates(read_file(indoorgml_file("v101_room.gml")), 1e7));
  const auto result = map_info(path("far.gml"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(
      result.out.find("large offsets moved to origin (10000000.000, 10000000.000, 10000000.000)"),
      std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("(0.000, 0.000, 0.000) .. (4.000, 3.000, 2.500) m"), std::string::npos)
      << result.out;
}

TEST_F(BadGml, DeepNestingIsRefusedWithoutStackOverflow) {
  std::string open, close;
  open.reserve(100000 * 7);
  close.reserve(100000 * 8);
  for (int i = 0; i < 100000; ++i) {
    open += "<x:d>";
    close += "</x:d>";
  }
  write_file(path("deep.gml"),
             replace_once(read_file(indoorgml_file("v101_room.gml")), "<gml:name>Room 1</gml:name>",
                          "<gml:name>Room 1</gml:name>" + open + close));
  expect_error(map_info(path("deep.gml")), 1,
               {"deep.gml: line 4, element x:d", "nested more than 256 levels"});
  expect_error(run("map-export " + quoted(path("deep.gml")) + " --obj " + quoted(path("o.obj"))), 1,
               {"deep.gml: line 4"});
}

TEST_F(BadGml, EntityBombIsNotExpanded) {
  // Billion laughs: ten levels of ten-fold entities. pugixml keeps unknown entity references
  // as text, so the coordinate is "&lol9;", not 10^9 copies of "lol".
  std::string dtd = "<!DOCTYPE IndoorFeatures [\n<!ENTITY lol0 \"lol\">\n";
  for (int i = 1; i <= 9; ++i) {
    dtd += "<!ENTITY lol" + std::to_string(i) + " \"";
    for (int k = 0; k < 10; ++k) dtd += "&lol" + std::to_string(i - 1) + ";";
    dtd += "\">\n";
  }
  dtd += "]>\n";
  std::string text =
      replace_once(room_with("&lol9; 0 2.5"), "<IndoorFeatures", dtd + "<IndoorFeatures");
  write_file(path("bomb.gml"), text);
  const auto start = std::chrono::steady_clock::now();
  const auto result = map_info(path("bomb.gml"));
  expect_error(result, 1,
               {"bomb.gml: line 22, element pos in Polygon (gml:id=\"R1-ceil\")",
                "not a number: \"&lol9;\""});
  EXPECT_LT(result.err.size(), 2000u);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
}

TEST_F(BadGml, WrongRootEmptyDirectoryAndMissingFile) {
  write_file(
      path("root.gml"),
      "<?xml version=\"1.0\"?>\n<CityModel xmlns=\"http://www.opengis.net/citygml/2.0\"/>\n");
  expect_error(map_info(path("root.gml")), 1,
               {"root.gml: line 2, element CityModel", "not an IndoorGML document"});
  write_file(path("empty.gml"), "");
  expect_error(map_info(path("empty.gml")), 1, {"empty.gml: empty file"});
  write_file(path("blank.gml"), "  \n\n ");
  expect_error(map_info(path("blank.gml")), 1, {"blank.gml: file holds only white space"});
  write_file(path("cut.gml"), read_file(indoorgml_file("v101_room.gml")).substr(0, 900));
  expect_error(map_info(path("cut.gml")), 1, {"cut.gml: line", "malformed XML"});
  expect_error(map_info(dir_), 1, {dir_.string() + ": is a directory"});
  expect_error(map_info(path("absent.gml")), 1, {"absent.gml: cannot open file"});
}

TEST_F(BadGml, EveryMapReadingCommandNamesTheBadModel) {
  write_file(path("nan.gml"), room_with("4.0 nan 2.5"));
  const std::string place = "nan.gml: line 10, element pos in Polygon (gml:id=\"R1-ceil\")";
  const std::string map = " --map " + quoted(path("nan.gml"));
  expect_error(run("map-export " + quoted(path("nan.gml")) + " --svg " + quoted(path("p.svg"))), 1,
               {place});
  expect_error(run("predict" + map + " --pose 1,1,1,0"), 1, {place});
  expect_error(run("simulate" + map + " --out " + quoted(path("s.pcap")) + " --truth " +
                   quoted(path("s.tum")) + " --duration 0.1"),
               1, {place});
  write_file(path("x.pcap"), "");
  expect_error(run("localize" + map + " --pcap " + quoted(path("x.pcap")) + " --out " +
                   quoted(path("e.tum")) + " --init 1,1,1,0"),
               1, {place});
}

// A gigabyte of pseudo-random bytes: every reader refuses it from its first bytes, at once and
// without reading it into memory.
TEST_F(BadInputCli, GigabyteOfGarbage) {
  std::vector<char> block(1 << 20);
  std::mt19937_64 rng(11);
  for (auto& c : block) c = static_cast<char>(rng());
  block[0] = 'G';
  {
    std::ofstream out(path("garbage.bin"), std::ios::binary);
    for (int i = 0; i < 1024; ++i)
      out.write(block.data(), static_cast<std::streamsize>(block.size()));
    ASSERT_TRUE(out.good()) << "cannot write 1 GiB in " << dir_;
  }
  const auto start = std::chrono::steady_clock::now();
  const std::string garbage = quoted(path("garbage.bin"));
  expect_error(run("map-info " + garbage), 1, {"garbage.bin: byte offset 0: not an XML file"});
  expect_error(run("decode " + garbage), 1, {"garbage.bin: file header"});
  expect_error(run("evaluate --truth " + garbage + " --est " + garbage), 1,
               {"garbage.bin: line 1"});
  expect_error(run("simulate --waypoints " + garbage + " --out " + quoted(path("s.pcap")) +
                   " --truth " + quoted(path("s.tum"))),
               1, {"garbage.bin: line 1"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
  fs::remove(path("garbage.bin"));
}

// ---------------------------------------------------------------------------------------------
// TUM trajectories (evaluate, localize --odom) and waypoint files (simulate)

class BadText : public BadInputCli {
 protected:
  static constexpr const char* kGood = "1 0 0 0 0 0 0 1\n2 1 0 0 0 0 0 1\n";
  GuardedRun evaluate_estimate(const std::string& text) {
    write_file(path("truth.tum"), kGood);
    write_file(path("est.tum"), text);
    return run("evaluate --truth " + quoted(path("truth.tum")) + " --est " +
               quoted(path("est.tum")));
  }
  GuardedRun simulate_waypoints(const std::string& text) {
    write_file(path("way.txt"), text);
    return run("simulate --waypoints " + quoted(path("way.txt")) + " --out " +
               quoted(path("w.pcap")) + " --truth " + quoted(path("w.tum")) + " --duration 0.1");
  }
};

TEST_F(BadText, TumFieldsNamedByLineAndColumn) {
  expect_error(evaluate_estimate("1 0 0 0 0 0 0 1\n2 abc 0 0 0 0 0 1\n"), 1,
               {"est.tum: line 2, field 2 (tx): 'abc' is not a number"});
  expect_error(evaluate_estimate("# t x y z qx qy qz qw\n1 0 0 nan 0 0 0 1\n"), 1,
               {"est.tum: line 2, field 4 (tz): 'nan' is not a finite number"});
  expect_error(evaluate_estimate("1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n"), 1,
               {"est.tum: line 2: expected 8 numbers", "found 7 fields"});
  expect_error(evaluate_estimate("1 0 0 0 0 0 0 1 7\n"), 1, {"est.tum: line 1:", "found 9 fields"});
  expect_error(evaluate_estimate("2 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n"), 1,
               {"est.tum: line 2: timestamp goes backwards"});
  expect_error(evaluate_estimate("1 0 0 0 0 0 0 1\n2 0 0 0 0.5 0 0 0.5\n"), 1,
               {"est.tum: line 2: quaternion norm 0.707107 is not 1"});
  expect_error(evaluate_estimate("1 0 0 0 0 0 0 0\n"), 1, {"est.tum: line 1: quaternion norm 0"});
  expect_error(evaluate_estimate("# nothing\n"), 1, {"est.tum: no poses in the file"});
  expect_error(
      run("evaluate --truth " + quoted(path("absent.tum")) + " --est " + quoted(path("est.tum"))),
      105, {"absent.tum"});
}

TEST_F(BadText, EvaluateSweepFileNamedByLine) {
  write_file(path("sweep.txt"), "particles = 100\nfoo = bar\n");
  expect_error(run("evaluate --sweep " + quoted(path("sweep.txt")) + " --out " + quoted(path("o"))),
               1, {"sweep.txt: line 2: unknown key 'foo'"});
  write_file(path("sweep.txt"), "# sweep\n\x01\x02 garbage\n");
  expect_error(run("evaluate --sweep " + quoted(path("sweep.txt")) + " --out " + quoted(path("o"))),
               1, {"sweep.txt: line 2"});
}

TEST_F(BadText, LocalizeOdometryIsChecked) {
  make_clean_capture();
  write_file(path("odom.tum"), "1 0 0 0 0 0 0 1\n2 x 0 0 0 0 0 1\n");
  expect_error(
      run("localize --pcap " + quoted(path("clean.pcap")) + " --out " + quoted(path("e.tum")) +
          " --odom " + quoted(path("odom.tum")) + " --init 9,2,0.8,90"),
      1, {"odom.tum: line 2, field 2 (tx)"});
}

TEST_F(BadText, LocalizeBadCaptureIsAnError) {
  write_file(path("magic.pcap"), std::string(4096, 'x'));
  expect_error(run("localize --pcap " + quoted(path("magic.pcap")) + " --out " +
                   quoted(path("e.tum")) + " --init 9,2,0.8,90"),
               1, {"magic.pcap: file header"});
}

TEST_F(BadText, WaypointFilesNamedByLine) {
  expect_error(simulate_waypoints("9 2\n10 abc\n"), 1,
               {"way.txt: line 2", "'abc' is not a finite number"});
  expect_error(simulate_waypoints("9 2\n10 nan\n"), 1,
               {"way.txt: line 2", "'nan' is not a finite number"});
  expect_error(simulate_waypoints("9 2 0 0 5\n"), 1, {"way.txt: line 1", "got 5 numbers"});
  expect_error(simulate_waypoints("9\n"), 1, {"way.txt: line 1", "got 1 numbers"});
  expect_error(simulate_waypoints("# none\n"), 1, {"way.txt: no waypoints"});
  expect_error(simulate_waypoints("9 2\n1e300 2\n"), 1,
               {"way.txt: waypoint 2", "outside the building"});
  expect_error(simulate_waypoints("9 2\n500 500\n"), 1,
               {"way.txt: waypoint 2", "outside the building"});
}

}  // namespace
}  // namespace conicloc::test
