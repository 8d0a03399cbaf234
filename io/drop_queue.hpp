#pragma once
// A bounded hand-over between a producer that must never wait (a live sensor's receiving thread)
// and a consumer that may fall behind (the filter). When the queue is full, push() drops the
// oldest item whole and counts it: the consumer always gets the newest data, and an item is
// either delivered complete or not at all.
//
// Example:
//   io::DropQueue<sensor::Scan> scans(2);
//   producer: scans.push(std::move(scan));  ...  scans.close();
//   consumer: while (auto scan = scans.pop()) localizer.update(*scan);

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>

namespace conicloc::io {

template <typename T>
class DropQueue {
 public:
  /// Precondition: capacity ≥ 1.
  explicit DropQueue(std::size_t capacity) : capacity_(capacity < 1 ? 1 : capacity) {}

  /// Never waits for the consumer. Returns true when an older item was dropped to make room.
  bool push(T item) {
    bool dropped = false;
    {
      const std::lock_guard lock(mutex_);
      if (items_.size() >= capacity_) {
        items_.pop_front();
        ++dropped_;
        dropped = true;
      }
      items_.push_back(std::move(item));
      ++pushed_;
    }
    ready_.notify_one();
    return dropped;
  }

  /// Waits for the oldest item; nullopt once close() was called and every item was taken.
  std::optional<T> pop() {
    std::unique_lock lock(mutex_);
    ready_.wait(lock, [this] { return !items_.empty() || closed_; });
    if (items_.empty()) return std::nullopt;
    T item = std::move(items_.front());
    items_.pop_front();
    return item;
  }

  /// No more items will come; pop() returns what is left, then nullopt.
  void close() {
    {
      const std::lock_guard lock(mutex_);
      closed_ = true;
    }
    ready_.notify_all();
  }

  std::size_t dropped() const {
    const std::lock_guard lock(mutex_);
    return dropped_;
  }
  /// Items ever pushed, dropped ones included.
  std::size_t pushed() const {
    const std::lock_guard lock(mutex_);
    return pushed_;
  }
  std::size_t capacity() const { return capacity_; }

 private:
  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<T> items_;
  std::size_t dropped_ = 0;
  std::size_t pushed_ = 0;
  bool closed_ = false;
};

}  // namespace conicloc::io
