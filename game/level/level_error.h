// Errors of the level reader: one line naming the file and where in it, then what is wrong,
// "levels/arena.tmj: layer 'walls': object 12: polygon crosses itself (edges 2 and 5)".
// Thrown for every problem of a map or tileset file, in release builds too; the commands catch
// it and print "ricochet: " before it.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include "game/quote.h"  // quoteName: names from the file in messages

namespace game {

class LevelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Where in which file a value sits: the file, then "layer 'walls'", "object 12", "property
// 'friction'", ... Copied and extended as the reader descends, so every message says the path.
class ErrorContext {
 public:
  explicit ErrorContext(std::string file) : file_(std::move(file)) {}
  ErrorContext in(const std::string& part) const {
    ErrorContext c = *this;
    c.where_ += (c.where_.empty() ? "" : ": ") + part;
    return c;
  }
  // Throws LevelError "FILE: WHERE: what", newlines in `what` flattened to spaces.
  [[noreturn]] void fail(const std::string& what) const;
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::string where_;
};

}  // namespace game
