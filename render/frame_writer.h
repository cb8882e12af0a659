// Writes numbered frames as PNG files on a worker thread, so the caller draws the next frame
// while the last one is encoded.
//
// submit() hands an image over and returns at once unless `queueCapacity` frames are already
// waiting, then it blocks until one is written (backpressure: memory stays bounded however slow
// the disk). A write that fails (unwritable directory, full disk) stops the writer: the error
// is thrown from the next submit(), flush() or finish(), naming the file.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>

#include "render/image.h"
#include "render/png.h"

namespace render {

struct FrameWriterOptions {
  std::filesystem::path directory;  // created if missing
  std::string prefix = "frame_";    // files are <prefix><index, 6 digits>.png
  std::size_t queueCapacity = 4;    // frames waiting to be encoded, at most
  PngOptions png;
};

class FrameWriter {
 public:
  // Creates the directory if needed; throws std::runtime_error naming it when it cannot be
  // created or is not a directory.
  explicit FrameWriter(FrameWriterOptions options);
  // Writes what is queued, then stops; errors at this point are lost (call finish() to see them).
  ~FrameWriter();
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // Queues frame `index`; returns the path it will be written to.
  std::filesystem::path submit(std::int64_t index, Image image);
  // Waits until every queued frame is on disk.
  void flush();
  // flush(), then stops the worker. Later submits throw.
  void finish();

  struct Stats {
    std::int64_t framesWritten = 0;
    std::int64_t bytesWritten = 0;
    double encodeSeconds = 0;  // total time in encodePng
    double writeSeconds = 0;   // total time writing and renaming files
  };
  Stats stats() const;
  const std::filesystem::path& directory() const { return options_.directory; }

 private:
  struct Job {
    std::int64_t index = 0;
    Image image;
  };
  void run();
  void rethrowLocked();

  FrameWriterOptions options_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> queue_;
  bool busy_ = false;  // the worker holds a job outside the queue
  bool stopping_ = false;
  std::exception_ptr error_;
  Stats stats_;
  std::thread worker_;
};

}  // namespace render
