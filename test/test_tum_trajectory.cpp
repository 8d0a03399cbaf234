#include <gtest/gtest.h>

#include <sstream>

#include "io/input_error.hpp"
#include "io/tum_trajectory.hpp"

namespace ci = conicloc::io;

TEST(TumTrajectory, WriteReadRoundTrip) {
  ci::StampedPose a;
  a.time_s = 1700000000.123456;
  a.pose.linear() =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  a.pose.translation() = Eigen::Vector3d(1.25, -3.5, 0.7);
  std::stringstream text;
  ci::write_tum_line(text, a);
  const auto poses = ci::read_tum(text, "mem");
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_NEAR(poses[0].time_s, a.time_s, 1e-6);
  EXPECT_TRUE(poses[0].pose.isApprox(a.pose, 1e-8));
}

TEST(TumTrajectory, CommentsAndBlankLinesAreSkipped) {
  std::istringstream text("# header\n\n0 0 0 0 0 0 0 1\n  # indented comment\n1 1 0 0 0 0 0 1\n");
  EXPECT_EQ(ci::read_tum(text, "mem").size(), 2u);
}

TEST(TumTrajectory, BadLinesNameTheLine) {
  std::istringstream short_line("0 0 0 0 0 0 0 1\n1 2 3\n");
  try {
    ci::read_tum(short_line, "odom.tum");
    FAIL() << "expected InputError";
  } catch (const ci::InputError& e) {
    EXPECT_EQ(e.place(), "line 2");
    EXPECT_NE(std::string(e.what()).find("odom.tum"), std::string::npos);
  }
  std::istringstream bad_quaternion("0 0 0 0 0 0 0 2\n");
  EXPECT_THROW(ci::read_tum(bad_quaternion, "x"), ci::InputError);
  std::istringstream backwards("2 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n");
  EXPECT_THROW(ci::read_tum(backwards, "x"), ci::InputError);
  std::istringstream nan_value("0 nan 0 0 0 0 0 1\n");
  EXPECT_THROW(ci::read_tum(nan_value, "x"), ci::InputError);
  EXPECT_THROW(ci::read_tum(std::string("/nonexistent/file.tum")), ci::InputError);
}
