#include "game/session/recording_file.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <iterator>

#include "game/input_file.h"

namespace game {
namespace {

void putU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k)
    out.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
}

std::uint32_t getU32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

constexpr std::size_t kPreamble = sizeof kRecordingMagic + 4;  // magic and format
constexpr std::size_t kChunkOverhead = 12;                     // type, length, CRC

}  // namespace

std::string chunkTypeName(std::uint32_t type) {
  std::string name;
  for (int k = 0; k < 4; ++k) {
    const auto c = static_cast<char>(type >> (8 * k));
    name += (c >= 0x20 && c < 0x7F) ? c : '?';
  }
  while (!name.empty() && name.back() == ' ')
    name.pop_back();
  return name;
}

std::uint32_t crc32Of(std::span<const std::uint8_t> bytes, std::uint32_t crc) {
  // zlib takes the length as uInt: feed it in pieces that fit.
  uLong c = crc;
  while (!bytes.empty()) {
    const std::size_t n = std::min<std::size_t>(bytes.size(), 1u << 30);
    c = ::crc32(c, bytes.data(), static_cast<uInt>(n));
    bytes = bytes.subspan(n);
  }
  return static_cast<std::uint32_t>(c);
}

RecordingWriter::RecordingWriter(const std::string& path) : path_(path) {
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr)
    throw RecordingError(path + ": cannot create the file: " + std::strerror(errno));
  std::vector<std::uint8_t> preamble(std::begin(kRecordingMagic), std::end(kRecordingMagic));
  putU32(preamble, kRecordingFormat);
  if (std::fwrite(preamble.data(), 1, preamble.size(), file_) != preamble.size() ||
      std::fflush(file_) != 0)
    throw RecordingError(path + ": cannot write: " + std::strerror(errno));
}

RecordingWriter::~RecordingWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

void RecordingWriter::write(std::uint32_t type, std::span<const std::uint8_t> payload) {
  if (file_ == nullptr) throw RecordingError(path_ + ": cannot write: the file is closed");
  if (payload.size() > kMaxChunkBytes)
    throw RecordingError(path_ + ": a " + chunkTypeName(type) + " chunk of " +
                         std::to_string(payload.size()) + " bytes is over the limit");
  std::vector<std::uint8_t> head;
  putU32(head, type);
  putU32(head, static_cast<std::uint32_t>(payload.size()));
  std::vector<std::uint8_t> tail;
  putU32(tail, crc32Of(payload, crc32Of(head)));
  // One chunk, then flushed: a killed recorder leaves whole chunks behind it.
  if (std::fwrite(head.data(), 1, head.size(), file_) != head.size() ||
      (!payload.empty() &&
       std::fwrite(payload.data(), 1, payload.size(), file_) != payload.size()) ||
      std::fwrite(tail.data(), 1, tail.size(), file_) != tail.size() || std::fflush(file_) != 0)
    throw RecordingError(path_ + ": cannot write: " + std::strerror(errno));
}

void RecordingWriter::close() {
  if (file_ == nullptr) return;
  const int failed = std::fclose(file_);
  file_ = nullptr;
  if (failed != 0) throw RecordingError(path_ + ": cannot write: " + std::strerror(errno));
}

RecordingContents readRecording(std::span<const std::uint8_t> bytes, const std::string& name) {
  RecordingContents out;
  out.bytes = bytes.size();
  if (bytes.size() < kPreamble ||
      !std::equal(std::begin(kRecordingMagic), std::end(kRecordingMagic), bytes.begin(),
                  [](char a, std::uint8_t b) { return static_cast<std::uint8_t>(a) == b; }))
    throw RecordingError(name + ": not a ricochet recording");
  out.format = getU32(bytes.data() + sizeof kRecordingMagic);
  if (out.format != kRecordingFormat)
    throw RecordingError(name + ": recording format " + std::to_string(out.format) +
                         ", this ricochet reads format " + std::to_string(kRecordingFormat));
  std::size_t at = kPreamble;
  while (at < bytes.size()) {
    const std::size_t left = bytes.size() - at;
    const std::string where =
        "chunk " + std::to_string(out.chunks.size()) + " at byte " + std::to_string(at);
    if (left < kChunkOverhead) {
      out.damage = where + ": truncated (" + std::to_string(left) + " bytes of its head)";
      break;
    }
    const std::uint32_t type = getU32(bytes.data() + at);
    const std::uint32_t length = getU32(bytes.data() + at + 4);
    if (length > kMaxChunkBytes || length > left - kChunkOverhead) {
      out.damage = where + ": truncated (" + chunkTypeName(type) + " of " + std::to_string(length) +
                   " bytes, " + std::to_string(left - kChunkOverhead) + " left)";
      break;
    }
    const std::span<const std::uint8_t> head = bytes.subspan(at, 8);
    const std::span<const std::uint8_t> payload = bytes.subspan(at + 8, length);
    const std::uint32_t stored = getU32(bytes.data() + at + 8 + length);
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
    // Fuzzing builds only: mutated payloads must reach their parsers, not die at the CRC.
    const bool crcMatches = true;
    (void)stored;
    (void)head;
#else
    const bool crcMatches = crc32Of(payload, crc32Of(head)) == stored;
#endif
    if (!crcMatches) {
      out.damage = where + ": CRC mismatch (" + chunkTypeName(type) + ", " +
                   std::to_string(length) + " bytes)";
      break;
    }
    out.chunks.push_back({type, at, std::vector<std::uint8_t>(payload.begin(), payload.end())});
    at += kChunkOverhead + length;
  }
  return out;
}

std::vector<std::uint8_t> readRecordingBytes(const std::string& path) {
  std::vector<std::uint8_t> bytes;
  if (const auto why = readInputFile(path, kMaxRecordingBytes, bytes))
    throw RecordingError(path + ": " + *why);
  return bytes;
}

RecordingContents readRecording(const std::string& path) {
  return readRecording(readRecordingBytes(path), path);
}

}  // namespace game
