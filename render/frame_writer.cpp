#include "render/frame_writer.h"

#include <chrono>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace render {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

FrameWriter::FrameWriter(FrameWriterOptions options) : options_(std::move(options)) {
  if (options_.queueCapacity == 0) {
    throw std::invalid_argument("render: FrameWriter queue capacity must be at least 1");
  }
  const std::filesystem::path& dir = options_.directory;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    throw std::runtime_error("render: cannot use '" + dir.string() + "' as the frame directory: " +
                             (ec ? ec.message() : std::string("not a directory")));
  }
  worker_ = std::thread([this] { run(); });
}

FrameWriter::~FrameWriter() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  if (worker_.joinable()) worker_.join();
}

void FrameWriter::rethrowLocked() {
  if (error_) std::rethrow_exception(error_);
}

std::filesystem::path FrameWriter::submit(std::int64_t index, Image image) {
  std::filesystem::path path = options_.directory / frameFileName(index, options_.prefix);
  std::unique_lock lock(mutex_);
  changed_.wait(lock,
                [&] { return error_ || stopping_ || queue_.size() < options_.queueCapacity; });
  rethrowLocked();
  if (stopping_) throw std::logic_error("render: FrameWriter::submit after finish()");
  queue_.push_back(Job{index, std::move(image)});
  lock.unlock();
  changed_.notify_all();
  return path;
}

void FrameWriter::flush() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return error_ || (queue_.empty() && !busy_); });
  rethrowLocked();
}

void FrameWriter::finish() {
  {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return error_ || (queue_.empty() && !busy_); });
    stopping_ = true;
  }
  changed_.notify_all();
  if (worker_.joinable()) worker_.join();
  std::lock_guard lock(mutex_);
  rethrowLocked();
}

FrameWriter::Stats FrameWriter::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

void FrameWriter::run() {
  for (;;) {
    Job job;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (queue_.empty() || error_) return;  // stopping, all written (or given up)
      job = std::move(queue_.front());
      queue_.pop_front();
      busy_ = true;
    }
    changed_.notify_all();  // a slot is free
    std::filesystem::path path = options_.directory / frameFileName(job.index, options_.prefix);
    try {
      auto start = std::chrono::steady_clock::now();
      std::vector<std::uint8_t> bytes = encodePng(job.image, options_.png);
      double encode = secondsSince(start);
      start = std::chrono::steady_clock::now();
      writeFileAtomically(path, bytes);
      double write = secondsSince(start);
      std::lock_guard lock(mutex_);
      ++stats_.framesWritten;
      stats_.bytesWritten += static_cast<std::int64_t>(bytes.size());
      stats_.encodeSeconds += encode;
      stats_.writeSeconds += write;
      busy_ = false;
    } catch (...) {
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
      queue_.clear();
      busy_ = false;
    }
    changed_.notify_all();
  }
}

}  // namespace render
