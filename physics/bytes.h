// Ricochet physics: little-endian bytes for snapshots, the same on every platform.
//
// Floats go as their IEEE bits, so a value read back is the value written, NaN payloads and
// signed zeros included. A reader that runs out, or is asked for a count larger than what is
// left, throws std::invalid_argument naming what it was reading: a truncated or corrupt input
// can never make it read past its end or allocate without bound.
#pragma once

#include <bit>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace rc {

// FNV-1a, 64-bit (Fowler, Noll and Vo): the hashes of world and match states, levels, and the
// piles' constraint layout (which mixes a word at a time with the same constants).
inline constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ull;
inline constexpr std::uint64_t kFnvPrime = 0x100000001b3ull;
// FNV-1a over bytes, continuing from `h`.
inline std::uint64_t fnv1a(std::span<const std::uint8_t> bytes, std::uint64_t h = kFnvOffset) {
  for (const std::uint8_t b : bytes) {
    h ^= b;
    h *= kFnvPrime;
  }
  return h;
}

class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(out) {}
  void u8(std::uint8_t v) { out_.push_back(v); }
  void boolean(bool v) { u8(v ? 1 : 0); }
  void u16(std::uint16_t v) { little(v, 2); }
  void u32(std::uint32_t v) { little(v, 4); }
  void i32(std::int32_t v) { little(static_cast<std::uint32_t>(v), 4); }
  void u64(std::uint64_t v) { little(v, 8); }
  void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void count(std::size_t n) { u32(static_cast<std::uint32_t>(n)); }

 private:
  void little(std::uint64_t v, int bytes) {
    for (int k = 0; k < bytes; ++k)
      out_.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  std::vector<std::uint8_t>& out_;
};

class ByteReader {
 public:
  ByteReader(std::span<const std::uint8_t> in, const char* what) : in_(in), what_(what) {}
  std::uint8_t u8() { return static_cast<std::uint8_t>(little(1)); }
  bool boolean() {
    const std::uint8_t v = u8();
    if (v > 1) fail("a flag is " + std::to_string(v));
    return v == 1;
  }
  std::uint16_t u16() { return static_cast<std::uint16_t>(little(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(little(4)); }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  std::uint64_t u64() { return little(8); }
  float f32() { return std::bit_cast<float>(u32()); }
  double f64() { return std::bit_cast<double>(u64()); }
  // A count of items of at least `itemBytes` each: refused when what is left cannot hold them.
  std::size_t count(std::size_t itemBytes) {
    const std::uint32_t n = u32();
    if (itemBytes > 0 && n > (in_.size() - pos_) / itemBytes)
      fail("a count of " + std::to_string(n) + " exceeds what is left");
    return n;
  }
  std::size_t position() const { return pos_; }
  bool atEnd() const { return pos_ == in_.size(); }
  [[noreturn]] void fail(const std::string& why) const {
    throw std::invalid_argument(std::string(what_) + ": " + why + " (at byte " +
                                std::to_string(pos_) + ")");
  }

 private:
  std::uint64_t little(int bytes) {
    if (in_.size() - pos_ < static_cast<std::size_t>(bytes)) fail("truncated");
    std::uint64_t v = 0;
    for (int k = 0; k < bytes; ++k)
      v |= static_cast<std::uint64_t>(in_[pos_ + static_cast<std::size_t>(k)]) << (8 * k);
    pos_ += static_cast<std::size_t>(bytes);
    return v;
  }
  std::span<const std::uint8_t> in_;
  std::size_t pos_ = 0;
  const char* what_;
};

}  // namespace rc
