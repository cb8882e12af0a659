// The recording container (game/session/recording_file.h): chunks written are read back as they
// were; a file cut anywhere reads up to its last whole chunk and says where it was cut; a
// flipped bit is caught by the chunk's CRC; files that are not recordings are refused by name.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "game/session/recording_file.h"
#include "physics/random.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace recording_file_test {

using game::RecordingContents;

std::filesystem::path scratch(const char* name) {
  return std::filesystem::temp_directory_path() / name;
}

std::vector<std::uint8_t> fileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A recording of a few chunks of different sizes (an empty one among them).
std::vector<std::vector<std::uint8_t>> writeSample(const std::filesystem::path& path) {
  rc::Random rng(21);
  std::vector<std::vector<std::uint8_t>> payloads;
  game::RecordingWriter w(path.string());
  for (std::size_t size : {40u, 0u, 600u, 7u, 3000u}) {
    std::vector<std::uint8_t> p(size);
    for (std::uint8_t& b : p)
      b = static_cast<std::uint8_t>(rng.below(256));
    w.write(size == 0 ? game::kChunkEnd : game::kChunkInputs, p);
    payloads.push_back(p);
  }
  w.close();
  return payloads;
}

TEST(RecordingFile, ChunksReadBackAsWritten) {
  const auto path = scratch("ricochet_recording_sample.rec");
  const auto payloads = writeSample(path);
  const RecordingContents r = game::readRecording(path.string());
  EXPECT_FALSE(r.damage.has_value());
  EXPECT_EQ(r.format, game::kRecordingFormat);
  ASSERT_EQ(r.chunks.size(), payloads.size());
  for (std::size_t k = 0; k < payloads.size(); ++k)
    EXPECT_EQ(r.chunks[k].payload, payloads[k]);
  EXPECT_EQ(r.chunks[1].type, game::kChunkEnd);
  EXPECT_EQ(game::chunkTypeName(game::kChunkEnd), "END");
  EXPECT_EQ(r.bytes, std::filesystem::file_size(path));
  // zlib's CRC-32 of "123456789" is the standard check value.
  const std::string check = "123456789";
  EXPECT_EQ(game::crc32Of({reinterpret_cast<const std::uint8_t*>(check.data()), check.size()}),
            0xCBF43926u);
}

// Cut at every byte: the whole chunks before the cut read back, the damage names the chunk and
// the byte where it begins; a cut exactly between chunks is a shorter, undamaged recording.
TEST(RecordingFile, EveryCutReadsUpToTheLastWholeChunk) {
  const auto path = scratch("ricochet_recording_cut.rec");
  const auto payloads = writeSample(path);
  const std::vector<std::uint8_t> whole = fileBytes(path);
  std::vector<std::size_t> ends;  // where each chunk ends
  std::size_t at = 12;
  for (const auto& p : payloads)
    ends.push_back(at += 12 + p.size());
  for (std::size_t n = 0; n < whole.size(); ++n) {
    const std::span<const std::uint8_t> cut(whole.data(), n);
    if (n < 12) {
      EXPECT_THROW(game::readRecording(cut, "cut"), game::RecordingError) << n;
      continue;
    }
    const RecordingContents r = game::readRecording(cut, "cut");
    std::size_t whole_chunks = 0;
    while (whole_chunks < ends.size() && ends[whole_chunks] <= n)
      ++whole_chunks;
    ASSERT_EQ(r.chunks.size(), whole_chunks) << n;
    const bool between = n == 12 || (whole_chunks > 0 && ends[whole_chunks - 1] == n);
    ASSERT_EQ(r.damage.has_value(), !between) << n;
    if (r.damage) {
      EXPECT_NE(r.damage->find("chunk " + std::to_string(whole_chunks) + " at byte"),
                std::string::npos)
          << *r.damage;
    }
  }
}

// A flipped bit anywhere in a chunk (type, length, payload or CRC) stops the reading at that
// chunk; the chunks before it are whole.
TEST(RecordingFile, FlippedBitsAreCaught) {
  const auto path = scratch("ricochet_recording_flip.rec");
  writeSample(path);
  const std::vector<std::uint8_t> whole = fileBytes(path);
  const RecordingContents good = game::readRecording(whole, "good");
  for (std::size_t i = 12; i < whole.size(); ++i) {
    std::vector<std::uint8_t> bad = whole;
    bad[i] ^= static_cast<std::uint8_t>(1u << (i % 8));
    const RecordingContents r = game::readRecording(bad, "bad");
    ASSERT_TRUE(r.damage.has_value()) << i;
    ASSERT_LT(r.chunks.size(), good.chunks.size()) << i;
    for (std::size_t k = 0; k < r.chunks.size(); ++k)
      ASSERT_EQ(r.chunks[k].payload, good.chunks[k].payload);
  }
}

TEST(RecordingFile, OtherFilesAreRefusedByName) {
  auto message = [](const std::string& path) {
    try {
      game::readRecording(path);
    } catch (const game::RecordingError& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  const auto dir = std::filesystem::temp_directory_path();
  EXPECT_EQ(message(dir.string()), dir.string() + ": cannot open the file: it is a directory");
  const auto missing = (dir / "ricochet_no_such.rec").string();
  EXPECT_EQ(message(missing), missing + ": cannot open the file: it does not exist");
  const auto text = dir / "ricochet_not_a_recording.rec";
  std::ofstream(text) << "{\"bodies\": []}";
  EXPECT_EQ(message(text.string()), text.string() + ": not a ricochet recording");
  const auto later = dir / "ricochet_format_9.rec";
  {
    std::ofstream out(later, std::ios::binary);
    out.write(game::kRecordingMagic, 8);
    const char format[4] = {9, 0, 0, 0};
    out.write(format, 4);
  }
  EXPECT_EQ(message(later.string()),
            later.string() + ": recording format 9, this ricochet reads format 1");
}

}  // namespace recording_file_test
