#include "game/session/recording.h"

#include <zlib.h>

#include <algorithm>
#include <filesystem>
#include <limits>

#include "game/match/match_snapshot.h"
#include "game/quote.h"
#include "physics/bytes.h"
#include "physics/integrate.h"

namespace game {
namespace {

void putText(rc::ByteWriter& w, std::vector<std::uint8_t>& out, const std::string& text) {
  w.count(text.size());
  out.insert(out.end(), text.begin(), text.end());
}

std::string getText(rc::ByteReader& r, std::span<const std::uint8_t> bytes, const char* what) {
  const std::size_t n = r.count(1);
  if (n > kMaxHeaderText)
    r.fail(std::string(what) + " of " + std::to_string(n) + " bytes is over the limit");
  const std::size_t at = r.position();
  for (std::size_t k = 0; k < n; ++k)
    r.u8();
  return std::string(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                     bytes.begin() + static_cast<std::ptrdiff_t>(at + n));
}

// An integer field of the header within [lo, hi], or the header is refused.
int bounded(rc::ByteReader& r, const char* what, std::int64_t lo, std::int64_t hi) {
  const auto v = static_cast<std::int64_t>(static_cast<std::int32_t>(r.u32()));
  if (v < lo || v > hi)
    r.fail(std::string(what) + " is " + std::to_string(v) + ", not " + std::to_string(lo) + " to " +
           std::to_string(hi));
  return static_cast<int>(v);
}

std::vector<std::uint8_t> encodeHeader(const RecordingHeader& h) {
  std::vector<std::uint8_t> out;
  rc::ByteWriter w(out);
  putText(w, out, h.program);
  w.u32(h.simulation);
  putText(w, out, h.level);
  w.u64(h.levelHash);
  putText(w, out, h.weaponsSource);
  putText(w, out, h.weaponsText);
  w.u64(h.seed);
  w.i32(h.players);
  w.i32(h.bots);
  w.i32(h.actors);
  w.i32(h.ticksPerSecond);
  w.i32(h.hashEvery);
  w.i32(h.keyframeEvery);
  w.i32(h.inputsPerChunk);
  w.i32(h.substeps);
  putText(w, out, h.integrator);
  return out;
}

RecordingHeader decodeHeader(std::span<const std::uint8_t> bytes) {
  rc::ByteReader r(bytes, "its header");
  RecordingHeader h;
  h.program = getText(r, bytes, "the program's name");
  h.simulation = r.u32();
  if (h.simulation != kSimulationVersion)
    r.fail("recorded by " + quoteName(h.program) + " with simulation version " +
           std::to_string(h.simulation) + "; this ricochet replays version " +
           std::to_string(kSimulationVersion) + " (record it again with this one)");
  h.level = getText(r, bytes, "the level's path");
  if (h.level.empty()) r.fail("it names no level");
  h.levelHash = r.u64();
  h.weaponsSource = getText(r, bytes, "the weapon table's name");
  h.weaponsText = getText(r, bytes, "the weapon table");
  h.seed = r.u64();
  h.players = bounded(r, "the number of players", 0, kMaxRecordedPlayers);
  h.bots = bounded(r, "the number of bots", 0, kMaxRecordedBots);
  h.actors = bounded(r, "the number of actors", 0, kMaxRecordedPlayers + kMaxRecordedBots);
  h.ticksPerSecond = bounded(r, "ticks per second", kTicksPerSecond, kTicksPerSecond);
  h.hashEvery = bounded(r, "the hash interval", 1, 1 << 20);
  h.keyframeEvery = bounded(r, "the keyframe interval", 1, 1 << 20);
  h.inputsPerChunk = bounded(r, "ticks per input chunk", 1, 1 << 16);
  h.substeps = bounded(r, "substeps", 0, 64);
  h.integrator = getText(r, bytes, "the integrator's name");
  if (!r.atEnd())
    r.fail("it has " + std::to_string(bytes.size() - r.position()) +
           " bytes more than a header holds");
  return h;
}

std::string chunkName(const RecordingChunk& c, std::size_t index) {
  return "chunk " + std::to_string(index) + " (" + chunkTypeName(c.type) + ") at byte " +
         std::to_string(c.offset);
}

}  // namespace

std::span<const PlayerInput> Recording::inputsAt(std::int64_t tick) const {
  const auto players = static_cast<std::size_t>(header.players);
  if (tick < 0 || tick >= ticks) return {};
  return std::span<const PlayerInput>(inputs).subspan(static_cast<std::size_t>(tick) * players,
                                                      players);
}

const Keyframe* Recording::keyframeAtOrBefore(std::int64_t tick) const {
  const Keyframe* best = nullptr;
  for (const Keyframe& k : keyframes)
    if (k.tick <= tick) best = &k;
  return best;
}

Recording parseRecording(std::span<const std::uint8_t> bytes, const std::string& name) {
  RecordingContents contents = readRecording(bytes, name);
  Recording out;
  out.path = name;
  out.bytes = contents.bytes;
  out.damage = contents.damage;
  if (contents.chunks.empty() || contents.chunks.front().type != kChunkHeader)
    throw RecordingError(name + ": " +
                         (contents.damage ? "its header is damaged: " + *contents.damage
                                          : std::string("it has no header")));
  try {
    out.header = decodeHeader(contents.chunks.front().payload);
  } catch (const std::invalid_argument& e) {
    throw RecordingError(name + ": " + e.what());
  }
  const RecordingHeader& h = out.header;
  if (h.actors != h.players + h.bots)
    throw RecordingError(name + ": its header is inconsistent: " + std::to_string(h.actors) +
                         " actors for " + std::to_string(h.players) + " players and " +
                         std::to_string(h.bots) + " bots");
  out.chunks = 1;
  const auto players = static_cast<std::size_t>(h.players);
  // The chunks after the header, each checked against what came before it; the first that makes
  // no sense ends the usable part, as a bad CRC does.
  for (std::size_t k = 1; k < contents.chunks.size(); ++k) {
    const RecordingChunk& c = contents.chunks[k];
    try {
      rc::ByteReader r(c.payload, "its payload");
      if (out.finished) r.fail("it follows the END chunk");
      if (c.type == kChunkInputs) {
        const auto first = static_cast<std::int64_t>(r.u64());
        const std::uint32_t n = r.u32();
        if (first != out.ticks)
          r.fail("its inputs start at tick " + std::to_string(first) + ", expected " +
                 std::to_string(out.ticks));
        if (n == 0 || n > static_cast<std::uint32_t>(h.inputsPerChunk))
          r.fail("it holds " + std::to_string(n) + " ticks, not 1 to " +
                 std::to_string(h.inputsPerChunk));
        if (c.payload.size() - r.position() != static_cast<std::size_t>(n) * players * kInputBytes)
          r.fail("its length does not fit " + std::to_string(n) + " ticks of " +
                 std::to_string(players) + " players");
        for (std::size_t i = 0; i < static_cast<std::size_t>(n) * players; ++i) {
          std::array<std::uint8_t, kInputBytes> record{};
          for (std::uint8_t& b : record)
            b = r.u8();
          out.inputs.push_back(fromBytes(record));
        }
        out.ticks += n;
      } else if (c.type == kChunkHash) {
        RecordedHash rh{static_cast<std::int64_t>(r.u64()), r.u64()};
        if (rh.tick < 1 || rh.tick > out.ticks ||
            (!out.hashes.empty() && rh.tick <= out.hashes.back().tick))
          r.fail("a hash of tick " + std::to_string(rh.tick) + " after " +
                 std::to_string(out.ticks) + " ticks of inputs");
        out.hashes.push_back(rh);
      } else if (c.type == kChunkKeyframe) {
        Keyframe kf;
        kf.tick = static_cast<std::int64_t>(r.u64());
        kf.hash = r.u64();
        kf.snapshotBytes = r.u32();
        if (kf.tick < 1 || kf.tick > out.ticks ||
            (!out.keyframes.empty() && kf.tick <= out.keyframes.back().tick))
          r.fail("a keyframe of tick " + std::to_string(kf.tick) + " after " +
                 std::to_string(out.ticks) + " ticks of inputs");
        if (kf.snapshotBytes == 0 || kf.snapshotBytes > kMaxChunkBytes)
          r.fail("a keyframe of " + std::to_string(kf.snapshotBytes) + " bytes");
        kf.snapshot.assign(c.payload.begin() + static_cast<std::ptrdiff_t>(r.position()),
                           c.payload.end());
        out.keyframes.push_back(std::move(kf));
      } else if (c.type == kChunkEnd) {
        const auto ticks = static_cast<std::int64_t>(r.u64());
        const std::uint64_t hash = r.u64();
        if (ticks != out.ticks)
          r.fail("it says " + std::to_string(ticks) + " ticks, the inputs hold " +
                 std::to_string(out.ticks));
        out.finished = true;
        out.finalHash = hash;
      } else {
        r.fail("a chunk of unknown type");
      }
      if (c.type != kChunkKeyframe && !r.atEnd()) r.fail("it is longer than its contents");
    } catch (const std::invalid_argument& e) {
      out.damage = chunkName(c, k) + ": " + e.what();
      break;
    }
    ++out.chunks;
  }
  return out;
}

Recording loadRecording(const std::string& path) {
  return parseRecording(readRecordingBytes(path), path);
}

std::vector<std::uint8_t> keyframeSnapshot(const Keyframe& keyframe, const std::string& name) {
  std::vector<std::uint8_t> out(keyframe.snapshotBytes);
  uLongf size = static_cast<uLongf>(out.size());
  const int result = ::uncompress(out.data(), &size, keyframe.snapshot.data(),
                                  static_cast<uLong>(keyframe.snapshot.size()));
  if (result != Z_OK || size != out.size())
    throw RecordingError(name + ": the keyframe of tick " + std::to_string(keyframe.tick) +
                         " does not inflate to its " + std::to_string(keyframe.snapshotBytes) +
                         " bytes");
  return out;
}

Recorder::Recorder(const std::string& path, const RecordingHeader& header)
    : writer_(path), header_(header) {
  writer_.write(kChunkHeader, encodeHeader(header_));
}

void Recorder::writeInputs() {
  if (buffered_ == 0) return;
  std::vector<std::uint8_t> payload;
  rc::ByteWriter w(payload);
  w.u64(static_cast<std::uint64_t>(firstBuffered_));
  w.u32(static_cast<std::uint32_t>(buffered_));
  payload.insert(payload.end(), inputs_.begin(), inputs_.end());
  writer_.write(kChunkInputs, payload);
  firstBuffered_ += buffered_;
  buffered_ = 0;
  inputs_.clear();
}

void Recorder::afterTick(const Match& match) {
  const MatchState& s = match.state();
  int players = 0;
  for (const Actor& a : s.actors) {
    if (a.kind != ActorKind::player) continue;
    const auto bytes = toBytes(a.input);
    inputs_.insert(inputs_.end(), bytes.begin(), bytes.end());
    ++players;
  }
  if (players != header_.players)
    throw RecordingError(writer_.path() + ": the match has " + std::to_string(players) +
                         " players, the header " + std::to_string(header_.players));
  ++buffered_;
  const std::int64_t tick = s.tick;
  // Inputs first: a hash or keyframe of tick t follows the inputs up to t in the file.
  const bool hashDue = tick % header_.hashEvery == 0;
  const bool keyframeDue = tick % header_.keyframeEvery == 0;
  if (buffered_ == header_.inputsPerChunk || hashDue || keyframeDue) writeInputs();
  if (hashDue) {
    std::vector<std::uint8_t> payload;
    rc::ByteWriter w(payload);
    w.u64(static_cast<std::uint64_t>(tick));
    w.u64(match.hash());
    writer_.write(kChunkHash, payload);
  }
  if (keyframeDue) {
    const MatchSnapshot snapshot = saveMatch(s);
    uLongf size = ::compressBound(static_cast<uLong>(snapshot.size()));
    std::vector<std::uint8_t> packed(size);
    if (::compress2(packed.data(), &size, snapshot.data(), static_cast<uLong>(snapshot.size()),
                    Z_BEST_SPEED) != Z_OK)
      throw RecordingError(writer_.path() + ": cannot compress the keyframe of tick " +
                           std::to_string(tick));
    packed.resize(size);
    std::vector<std::uint8_t> payload;
    rc::ByteWriter w(payload);
    w.u64(static_cast<std::uint64_t>(tick));
    w.u64(fnv1a(snapshot));
    w.u32(static_cast<std::uint32_t>(snapshot.size()));
    payload.insert(payload.end(), packed.begin(), packed.end());
    writer_.write(kChunkKeyframe, payload);
  }
}

void Recorder::finish(const Match& match) {
  writeInputs();
  std::vector<std::uint8_t> payload;
  rc::ByteWriter w(payload);
  w.u64(static_cast<std::uint64_t>(match.state().tick));
  w.u64(match.hash());
  writer_.write(kChunkEnd, payload);
  writer_.close();
}

RecordingHeader headerFor(const Match& match, const std::string& levelPath,
                          const std::string& recordingPath) {
  const MatchState& s = match.state();
  RecordingHeader h;
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path level = fs::absolute(levelPath, ec);
  const fs::path folder = fs::absolute(recordingPath, ec).parent_path();
  // Relative when the two share a folder below the root (a session beside its levels, as the
  // bundled ones are, moves with them); absolute otherwise.
  const fs::path relative = level.lexically_relative(folder);
  const auto climbs = std::count(relative.begin(), relative.end(), fs::path(".."));
  const fs::path below = folder.relative_path();
  const auto depth = std::distance(below.begin(), below.end());
  const bool useRelative = !ec && !relative.empty() && climbs < depth;
  h.level = (useRelative ? relative : level).generic_string();
  h.levelHash = s.levelHash;
  h.weaponsSource = s.weapons.source;
  h.weaponsText = s.weapons.text;
  h.seed = s.config.seed;
  h.players = h.bots = 0;
  for (const Actor& a : s.actors)
    (a.kind == ActorKind::player ? h.players : h.bots) += 1;
  h.actors = static_cast<int>(s.actors.size());
  h.substeps = s.world->def().substeps;
  h.integrator = std::string(rc::integratorName(s.world->def().integrator));
  return h;
}

}  // namespace game
