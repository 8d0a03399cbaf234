// io::DropQueue: bounded, never waits on push, drops the oldest whole item when full and counts
// it, hands the rest over in order, and ends after close().
#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

#include "io/drop_queue.hpp"

namespace conicloc::io {
namespace {

TEST(DropQueue, KeepsOrderWhileThereIsRoom) {
  DropQueue<int> queue(3);
  EXPECT_FALSE(queue.push(1));
  EXPECT_FALSE(queue.push(2));
  EXPECT_FALSE(queue.push(3));
  queue.close();
  EXPECT_EQ(queue.pop(), 1);
  EXPECT_EQ(queue.pop(), 2);
  EXPECT_EQ(queue.pop(), 3);
  EXPECT_EQ(queue.pop(), std::nullopt);
  EXPECT_EQ(queue.dropped(), 0u);
  EXPECT_EQ(queue.pushed(), 3u);
}

TEST(DropQueue, WhenFullDropsTheOldestWholeItemAndCountsIt) {
  DropQueue<std::vector<int>> queue(2);
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(queue.push(std::vector<int>(100, i)), i >= 2) << i;  // never waits
  }
  EXPECT_EQ(queue.dropped(), 5u);
  EXPECT_EQ(queue.pushed(), 7u);
  queue.close();
  // The two newest, each complete.
  EXPECT_EQ(queue.pop(), std::vector<int>(100, 5));
  EXPECT_EQ(queue.pop(), std::vector<int>(100, 6));
  EXPECT_EQ(queue.pop(), std::nullopt);
}

TEST(DropQueue, CapacityZeroActsAsOne) {
  DropQueue<int> queue(0);
  EXPECT_EQ(queue.capacity(), 1u);
  queue.push(1);
  EXPECT_TRUE(queue.push(2));
  queue.close();
  EXPECT_EQ(queue.pop(), 2);
}

TEST(DropQueue, PopWaitsForAProducerThread) {
  DropQueue<std::string> queue(1);
  std::thread producer([&] {
    queue.push("scan");
    queue.close();
  });
  EXPECT_EQ(queue.pop(), "scan");  // waits for the push (or gets it at once)
  EXPECT_EQ(queue.pop(), std::nullopt);
  producer.join();
}

TEST(DropQueue, EveryItemIsEitherDeliveredOrCountedDropped) {
  DropQueue<std::vector<int>> queue(2);
  constexpr int kItems = 2000;
  std::thread producer([&] {
    for (int i = 0; i < kItems; ++i) queue.push(std::vector<int>(16, i));
    queue.close();
  });
  std::size_t delivered = 0;
  int previous = -1;
  while (auto item = queue.pop()) {
    ASSERT_EQ(item->size(), 16u);
    for (const int value : *item) ASSERT_EQ(value, item->front());  // never a mix of two
    ASSERT_GT(item->front(), previous);                             // in order
    previous = item->front();
    ++delivered;
  }
  producer.join();
  EXPECT_EQ(delivered + queue.dropped(), static_cast<std::size_t>(kItems));
  EXPECT_EQ(previous, kItems - 1);  // the newest item always gets through
}

}  // namespace
}  // namespace conicloc::io
