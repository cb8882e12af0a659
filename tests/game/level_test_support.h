// What the level tests share: the bundled levels' paths, scratch directories for hand-written
// maps, and readers of what the loader made (chain loops among a body's shapes).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "game/level/level_error.h"
#include "physics/shapes.h"

namespace level_test {

inline std::string levelPath(const std::string& name) {
  return std::string(RICOCHET_SOURCE_DIR) + "/assets/levels/" + name;
}

// A fresh directory under the system's temporary directory, removed with everything in it.
class ScratchDir {
 public:
  ScratchDir() {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("ricochet_level_" + std::to_string(::getpid()) + "_" + std::to_string(++counter));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream out(file(name), std::ios::binary);
    out << text;
    return file(name);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The message of the LevelError `run` throws; a test failure if it throws something else or
// nothing.
inline std::string levelErrorOf(const std::function<void()>& run) {
  try {
    run();
  } catch (const game::LevelError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not a LevelError: " << e.what();
    return "";
  }
  ADD_FAILURE() << "no error";
  return "";
}

// Sizes of the closed chains among the shapes, in order: links follow each other
// (point2 == next point1) until one ends where its loop began.
inline std::vector<int> chainLoopSizes(const std::vector<rc::Shape>& shapes) {
  std::vector<int> sizes;
  int count = 0;
  rc::Vec2 first{};
  for (const rc::Shape& s : shapes) {
    if (s.type != rc::ShapeType::chainSegment) continue;
    const rc::Segment& seg = s.chainSegment.segment;
    if (count == 0) first = seg.point1;
    ++count;
    if (seg.point2 == first) {
      sizes.push_back(count);
      count = 0;
    }
  }
  if (count != 0) sizes.push_back(-count);  // an open chain: negative, for the tests to see
  return sizes;
}

inline int countShapes(const std::vector<rc::Shape>& shapes, rc::ShapeType type) {
  int n = 0;
  for (const rc::Shape& s : shapes)
    n += s.type == type ? 1 : 0;
  return n;
}

}  // namespace level_test
