// The container of a recorded session: a magic, a format version, then chunks, each with its
// type, its length and a CRC-32 (zlib's) of both and its payload. game/session/FORMAT.md
// describes the file; this is its writer and its reader.
//
// The writer appends a chunk and flushes it at once, so a recorder killed at any moment leaves
// a file whose whole chunks are all readable. The reader takes chunks in order and stops at the
// first that is truncated or whose CRC does not match, saying which and where; what came before
// is good. It never reads past the file, and a length field is checked against what is left
// before anything is allocated for it.
#pragma once

#include <cstdint>
#include <cstdio>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace game {

inline constexpr char kRecordingMagic[8] = {'R', 'I', 'C', 'O', 'C', 'H', 'E', 'T'};
inline constexpr std::uint32_t kRecordingFormat = 1;
// No chunk is longer: a keyframe of a large match is well under a megabyte.
inline constexpr std::uint32_t kMaxChunkBytes = 64u << 20;
// No recording is larger (a day of a 16-player match's inputs is 500 MB): the reader holds the
// file in memory.
inline constexpr std::uintmax_t kMaxRecordingBytes = std::uintmax_t{1} << 30;

// Chunk types, four ASCII characters read as a little-endian number.
constexpr std::uint32_t chunkType(const char (&tag)[5]) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(tag[0])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(tag[1])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(tag[2])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(tag[3])) << 24;
}
inline constexpr std::uint32_t kChunkHeader = chunkType("HEAD");
inline constexpr std::uint32_t kChunkInputs = chunkType("INPT");
inline constexpr std::uint32_t kChunkHash = chunkType("HASH");
inline constexpr std::uint32_t kChunkKeyframe = chunkType("KEYF");
inline constexpr std::uint32_t kChunkEnd = chunkType("END ");
std::string chunkTypeName(std::uint32_t type);

// A file that cannot be created or written, named with what failed.
class RecordingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class RecordingWriter {
 public:
  // Creates (truncates) the file and writes the magic and the format version.
  explicit RecordingWriter(const std::string& path);
  ~RecordingWriter();
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  // Appends one chunk and flushes it.
  void write(std::uint32_t type, std::span<const std::uint8_t> payload);
  // Closes the file, reporting a failure to write its last bytes.
  void close();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
};

struct RecordingChunk {
  std::uint32_t type = 0;
  std::uint64_t offset = 0;  // of its type field, in the file
  std::vector<std::uint8_t> payload;
};

struct RecordingContents {
  std::uint32_t format = 0;
  std::vector<RecordingChunk> chunks;  // every whole, checked chunk, in order
  std::uint64_t bytes = 0;             // the file's size
  // Set when reading stopped before the end of the file: what was wrong and where.
  std::optional<std::string> damage;
};

// Reads a recording. A file that is missing, a directory, not a recording or of another format
// throws RecordingError (one line naming the file); a damaged one returns what is good and says
// where the damage is.
RecordingContents readRecording(const std::string& path);
// The file's bytes, refused as readRecording(path) refuses: missing, a directory, over 1 GiB.
std::vector<std::uint8_t> readRecordingBytes(const std::string& path);
RecordingContents readRecording(std::span<const std::uint8_t> bytes, const std::string& name);

// zlib's CRC-32 of the bytes, continuing from crc (0 to start).
std::uint32_t crc32Of(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0);

}  // namespace game
