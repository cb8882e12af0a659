// Recorded sessions (game/session, game/match/match_snapshot): a recording replays to the same
// hash at every stored tick on every bundled level and from every keyframe; a match restored
// from its snapshot continues bit for bit; a changed input or a moved body is named by tick
// window, entity, body and field; the synctest passes, and fails on hidden state; every kind of
// damaged or hostile file is refused or played up to its damage with one line saying where.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "game/level/level_loader.h"
#include "game/level_test_support.h"
#include "game/match/match.h"
#include "game/match/match_snapshot.h"
#include "game/quote.h"
#include "game/session/batch.h"
#include "game/session/input_script.h"
#include "game/session/recording.h"
#include "game/session/replay.h"
#include "physics/bytes.h"
#include "physics/random.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace session_test {

using game::Recording;
using game::ReplayOptions;
using game::ReplayReport;
using game::Verdict;
using level_test::levelPath;
using level_test::ScratchDir;

struct RecordSpec {
  std::string level = "arena.tmj";
  int bots = 8, players = 1;
  std::int64_t ticks = 600;
  std::uint64_t seed = 1;
  int keyframeEvery = 120;
  std::function<void(game::MatchState&)> hook;  // the recorded run's only (a perturbation)
};

// Plays and records a match; returns its final hash.
std::uint64_t record(const std::string& path, const RecordSpec& spec) {
  game::MatchConfig config;
  config.bots = spec.bots;
  config.players = spec.players;
  config.seed = spec.seed;
  config.testHook = spec.hook;
  game::Match match(game::loadLevel(levelPath(spec.level)), config);
  game::RecordingHeader header = game::headerFor(match, levelPath(spec.level), path);
  header.keyframeEvery = spec.keyframeEvery;
  game::Recorder recorder(path, header);
  for (std::int64_t t = 0; t < spec.ticks; ++t) {
    match.tick();
    recorder.afterTick(match);
  }
  recorder.finish(match);
  return match.hash();
}

std::vector<std::uint8_t> bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

// The recording at `from` written again to `to` chunk by chunk, `edit` changing payloads: a
// forged file whose CRCs are all right.
void rewrite(const std::string& from, const std::string& to,
             const std::function<void(std::size_t index, std::uint32_t type,
                                      std::vector<std::uint8_t>& payload)>& edit) {
  const game::RecordingContents contents = game::readRecording(from);
  game::RecordingWriter w(to);
  for (std::size_t k = 0; k < contents.chunks.size(); ++k) {
    std::vector<std::uint8_t> payload = contents.chunks[k].payload;
    edit(k, contents.chunks[k].type, payload);
    w.write(contents.chunks[k].type, payload);
  }
  w.close();
}

void putU32(std::vector<std::uint8_t>& bytes, std::size_t at, std::uint32_t v) {
  for (int k = 0; k < 4; ++k)
    bytes[at + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(v >> (8 * k));
}

ReplayReport verify(const Recording& r, ReplayOptions options = {}) {
  options.verify = true;
  return game::replayRecording(r, options);
}

TEST(Session, RoundTripOnEveryBundledLevel) {
  const ScratchDir dir;
  for (const char* level : {"arena.tmj", "corridors.tmj", "maze.tmj"}) {
    RecordSpec spec;
    spec.level = level;
    const std::string path = dir.file(std::string(level) + ".rec");
    const std::uint64_t finalHash = record(path, spec);
    const Recording r = game::loadRecording(path);
    EXPECT_TRUE(r.finished) << level;
    EXPECT_FALSE(r.damage) << level;
    EXPECT_EQ(r.ticks, 600);
    EXPECT_EQ(r.hashes.size(), 10u);
    EXPECT_EQ(r.keyframes.size(), 5u);
    ASSERT_EQ(r.finalHash, finalHash);
    const ReplayReport report = verify(r);
    EXPECT_EQ(report.verdict, Verdict::ok) << level << ": " << report.message;
    EXPECT_EQ(report.hashesChecked, 10);
    EXPECT_EQ(report.finalHash, finalHash);
    // From every keyframe (and between them) to the end: the same end.
    for (const std::int64_t from : {120, 200, 480, 599}) {
      ReplayOptions seek;
      seek.from = from;
      const ReplayReport part = verify(r, seek);
      EXPECT_EQ(part.start, from / 120 * 120) << level << " from " << from;
      EXPECT_EQ(part.verdict, Verdict::ok) << part.message;
      EXPECT_EQ(part.finalHash, finalHash) << level << " from " << from;
    }
    // --to stops there, with the recorded hash of that tick.
    ReplayOptions upTo;
    upTo.to = 300;
    const ReplayReport head = verify(r, upTo);
    EXPECT_EQ(head.end, 300);
    EXPECT_EQ(head.finalHash, r.hashes[4].hash);
  }
}

TEST(Session, RestoredMatchContinuesBitForBit) {
  game::MatchConfig config;
  config.bots = 8;
  config.seed = 5;
  const game::Level level = game::loadLevel(levelPath("arena.tmj"));
  game::Match a(level, config), b(level, config);
  for (int t = 0; t < 400; ++t)
    a.tick();
  const game::MatchSnapshot saved = game::saveMatch(a.state());
  game::restoreMatch(b.state(), saved);
  EXPECT_EQ(b.hash(), a.hash());
  for (int t = 0; t < 400; ++t) {
    a.tick();
    b.tick();
    ASSERT_EQ(a.hash(), b.hash()) << "tick " << a.state().tick;
  }
  // A refused snapshot (cut, or of another match) leaves the match as it was.
  const std::uint64_t before = b.hash();
  for (const std::size_t cut : {std::size_t{0}, std::size_t{7}, saved.size() / 2, saved.size() - 1})
    EXPECT_THROW(game::restoreMatch(b.state(), std::span(saved).first(cut)),
                 game::MatchSnapshotError);
  game::MatchConfig fewer = config;
  fewer.bots = 4;
  game::Match other(level, fewer);
  EXPECT_THROW(game::restoreMatch(other.state(), saved), game::MatchSnapshotError);
  EXPECT_EQ(b.hash(), before);
}

// A player's input changed at a tick T: the hash of T's window of 60 ticks differs, and the
// keyframe at its end names the player's body.
TEST(Session, VerifyNamesTheWindowTheEntityAndTheFieldOfAChangedInput) {
  const ScratchDir dir;
  const std::string path = dir.file("input.rec");
  RecordSpec spec;
  spec.keyframeEvery = 60;
  record(path, spec);
  Recording r = game::loadRecording(path);
  // The first tick from 250 on at which the player is alive (a dead player's input does nothing).
  std::int64_t changed = -1;
  ReplayOptions look;
  look.from = 250;
  look.onTick = [&](const game::Match& m) {
    if (changed < 0 && m.state().actors[0].alive) changed = m.state().tick;
  };
  game::replayRecording(r, look);
  ASSERT_GE(changed, 250);
  ASSERT_LT(changed, 420);
  game::PlayerInput& in = r.inputs[static_cast<std::size_t>(changed)];  // one player a tick
  in.moveX = static_cast<std::int8_t>(in.moveX > 0 ? -127 : 127);
  const std::int64_t window = (changed / 60 + 1) * 60;
  const ReplayReport report = verify(r);
  ASSERT_EQ(report.verdict, Verdict::diverged);
  EXPECT_NE(report.message.find("tick " + std::to_string(window) + ": hash"), std::string::npos)
      << report.message;
  EXPECT_NE(
      report.message.find("ticks " + std::to_string(window - 59) + " to " + std::to_string(window)),
      std::string::npos)
      << report.message;
  ASSERT_FALSE(report.differences.empty());
  EXPECT_EQ(report.differences.front().what.rfind("actor 0 ('player 1') body ", 0), 0u)
      << report.differences.front().what;
  EXPECT_NE(report.differences.front().what.find("position"), std::string::npos);
}

// A crate pushed 0.25 m along x in the recorded run at tick 130 (a match of no actors, so
// nothing else moves): the replay names ticks 121-180, that crate's body and "position x".
TEST(Session, VerifyNamesTheBodyAndFieldThatWereChanged) {
  const ScratchDir dir;
  const std::string path = dir.file("moved.rec");
  RecordSpec spec;
  spec.bots = 0;
  spec.players = 0;
  spec.ticks = 300;
  spec.keyframeEvery = 60;
  std::string crate;
  spec.hook = [&](game::MatchState& s) {
    if (s.tick != 130) return;
    const game::PropState& p = s.props.front();
    const rc::Vec2 at = s.world->position(p.body);
    s.world->setTransform(p.body, at + rc::Vec2{0.25f, 0}, s.world->angle(p.body));
    crate = "body " + std::to_string(p.body.index) + " (";
  };
  record(path, spec);
  ASSERT_FALSE(crate.empty());
  const ReplayReport report = verify(game::loadRecording(path));
  ASSERT_EQ(report.verdict, Verdict::diverged);
  EXPECT_NE(report.message.find("ticks 121 to 180"), std::string::npos) << report.message;
  ASSERT_FALSE(report.differences.empty());
  const std::string& what = report.differences.front().what;
  EXPECT_EQ(what.rfind("prop " + crate, 0), 0u) << what;
  EXPECT_NE(what.find(" position x"), std::string::npos) << what;
}

TEST(Session, SynctestPassesAndFindsHiddenState) {
  const ScratchDir dir;
  const std::string path = dir.file("sync.rec");
  record(path, RecordSpec{});
  const Recording r = game::loadRecording(path);
  ReplayOptions options;
  options.synctest = true;
  options.to = 300;
  EXPECT_EQ(game::replayRecording(r, options).verdict, Verdict::ok);
  // State the hook keeps outside the match: a tick played twice sees it changed.
  int calls = 0;
  options.testHook = [calls](game::MatchState& s) mutable {
    if (++calls % 2 == 0) s.actors[0].aim += 0.001f;
  };
  const ReplayReport report = game::replayRecording(r, options);
  ASSERT_EQ(report.verdict, Verdict::desynced);
  EXPECT_NE(report.message.find("tick 1:"), std::string::npos) << report.message;
  ASSERT_FALSE(report.differences.empty());
  EXPECT_EQ(report.differences.front().what, "actor 0 ('player 1') aim");
}

// Files that are not recordings at all, or whose header cannot be used, are refused by name.
TEST(Session, UnusableFilesAreRefusedInOneLine) {
  const ScratchDir dir;
  const std::string good = dir.file("good.rec");
  RecordSpec spec;
  spec.ticks = 120;
  spec.bots = 2;
  record(good, spec);
  auto refusal = [](const std::string& path) -> std::string {
    try {
      game::loadRecording(path);
    } catch (const game::RecordingError& e) {
      return e.what();
    }
    return "(accepted)";
  };
  auto expectRefused = [&](const std::string& path, const std::string& words) {
    const std::string message = refusal(path);
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(words), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  expectRefused(dir.write("empty.rec", ""), "not a ricochet recording");
  expectRefused(dir.path().string(), "it is a directory");
  expectRefused(dir.file("missing.rec"), "does not exist");
  // A device has no size to check: /dev/zero was read until memory ran out.
  expectRefused("/dev/zero", "cannot open the file: it is not a regular file");
  expectRefused(dir.write("text.rec", "{\"not\": \"a recording\"}"), "not a ricochet recording");
  std::vector<std::uint8_t> future = bytesOf(good);
  putU32(future, 8, 99);
  writeBytes(dir.file("future.rec"), future);
  expectRefused(dir.file("future.rec"), "recording format 99, this ricochet reads format 1");

  // Forged headers with right CRCs: another simulation version, 2^31 players, a weapon table
  // that claims 2^31 bytes.
  auto forge = [&](const std::string& name, std::size_t offsetFromHead, std::uint32_t value) {
    rewrite(good, dir.file(name), [&](std::size_t k, std::uint32_t, std::vector<std::uint8_t>& p) {
      if (k == 0) putU32(p, offsetFromHead, value);
    });
    return dir.file(name);
  };
  const std::size_t program = 4 + std::string(game::kProgramVersion).size();
  expectRefused(forge("simulation.rec", program, 999),
                "simulation version 999; this ricochet replays version");
  const game::RecordingHeader& h = game::loadRecording(good).header;
  const std::size_t players = program + 4 + 4 + h.level.size() + 8 + 4 + h.weaponsSource.size() +
                              4 + h.weaponsText.size() + 8;
  expectRefused(forge("players.rec", players, 0x80000000u),
                "the number of players is -2147483648, not 0 to 16");
  expectRefused(forge("players2.rec", players, 0x7FFFFFFFu), "the number of players is 2147483647");
  expectRefused(
      forge("weapons.rec", program + 4 + 4 + h.level.size() + 8 + 4 + h.weaponsSource.size(),
            0x7FFFFFFFu),
      "exceeds what is left");
  // A damaged header is a refusal, not a damaged file.
  std::vector<std::uint8_t> flipped = bytesOf(good);
  flipped[12 + 8 + 3] ^= 0x10;
  writeBytes(dir.file("head.rec"), flipped);
  expectRefused(dir.file("head.rec"), "its header is damaged: chunk 0 at byte 12: CRC mismatch");
}

// What `ricochet CMD ARGS` prints: stdout, stderr and the exit code.
struct CommandResult {
  std::string out, err;
  int code = -1;
};
CommandResult runRicochet(const ScratchDir& dir, const std::string& args) {
  const std::string errFile = dir.file("stderr.txt");
  const std::string command = std::string(RICOCHET_EXE) + " " + args + " 2>" + errFile;
  CommandResult result;
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  std::size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof buffer, pipe)) > 0)
    result.out.append(buffer, got);
  const int status = ::pclose(pipe);
  result.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(errFile, std::ios::binary);
  result.err.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return result;
}

// A header's texts are the file's, not ours: a forged level name of a megabyte with a newline
// and a terminal escape in it was printed whole and raw by info and in replay's refusal. Now
// quoted, escaped and cut (game/quote.h), by the library and by both commands.
TEST(Session, HeaderTextsAreQuotedInEveryMessage) {
  const ScratchDir dir;
  game::MatchConfig config;
  config.bots = 1;
  game::Match match(game::loadLevel(levelPath("arena.tmj")), config);
  const std::string path = dir.file("forged.rec");
  game::RecordingHeader header = game::headerFor(match, levelPath("arena.tmj"), path);
  const std::string forged = "a\nb\x1b[31m" + std::string(game::kMaxHeaderText - 16, 'x');
  header.level = forged;
  header.weaponsSource = forged;
  {
    game::Recorder recorder(path, header);
    for (int t = 0; t < 10; ++t) {
      match.tick();
      recorder.afterTick(match);
    }
    recorder.finish(match);
  }
  const Recording r = game::loadRecording(path);
  ASSERT_EQ(r.header.level, forged);
  const std::string quoted =
      "'a\\x0ab\\x1b[31m" + std::string(game::kMaxQuotedBytes - 8, 'x') + "...'";
  auto expectShort = [&](const std::string& text, std::size_t lines) {
    EXPECT_EQ(static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')), lines) << text;
    EXPECT_EQ(text.find('\x1b'), std::string::npos) << text;
    EXPECT_LT(text.size(), 200 * lines) << text.substr(0, 400);
  };
  try {
    verify(r);
    ADD_FAILURE() << "a level nowhere was accepted";
  } catch (const game::RecordingError& e) {
    EXPECT_EQ(std::string(e.what()),
              path + ": its level " + quoted + " is not where it says (give it with --level)");
  }
  const CommandResult info = runRicochet(dir, "info " + path);
  EXPECT_EQ(info.code, 0) << info.err;
  expectShort(info.out, 7);
  EXPECT_NE(info.out.find("\nlevel " + quoted + " (content hash "), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("\nweapons from " + quoted + ", seed 1"), std::string::npos) << info.out;
  const CommandResult replay = runRicochet(dir, "replay " + path);
  EXPECT_EQ(replay.code, 1);
  EXPECT_EQ(replay.out, "");
  expectShort(replay.err, 1);
  EXPECT_NE(replay.err.find("its level " + quoted + " is not where it says"), std::string::npos)
      << replay.err.substr(0, 400);
}

// What is read line by line (an input script, a list of recordings) may be a pipe or a device:
// a line is bounded while it is read, not after. std::getline took /dev/zero's one endless line
// until memory ran out.
TEST(Session, EndlessLinesAreRefused) {
  std::ifstream zero("/dev/zero", std::ios::binary);
  game::InputScript script(zero, "/dev/zero", 1);
  try {
    script.inputsFor(0);
    ADD_FAILURE() << "an endless line was accepted";
  } catch (const game::InputScriptError& e) {
    EXPECT_STREQ(e.what(), "/dev/zero:1: the line is over 4096 characters");
  }
  try {
    game::batchFiles("/dev/zero");
    ADD_FAILURE() << "an endless line was accepted";
  } catch (const game::RecordingError& e) {
    EXPECT_STREQ(e.what(), "/dev/zero: line 1 is over 4096 characters: not a list of recordings");
  }
}

TEST(Session, LevelsThatAreMissingOrChangedAreRefused) {
  const ScratchDir dir;
  // A copy of the arena and its tileset beside the recording, then edited.
  for (const char* f : {"arena.tmj", "tiles.tsj", "tiles.png"})
    std::filesystem::copy_file(levelPath(f), dir.file(f));
  const std::string path = dir.file("arena.rec");
  game::MatchConfig config;
  config.bots = 2;
  game::Match match(game::loadLevel(dir.file("arena.tmj")), config);
  game::Recorder recorder(path, game::headerFor(match, dir.file("arena.tmj"), path));
  for (int t = 0; t < 60; ++t) {
    match.tick();
    recorder.afterTick(match);
  }
  recorder.finish(match);
  const Recording r = game::loadRecording(path);
  EXPECT_EQ(r.header.level, "arena.tmj");  // beside it: relative
  EXPECT_EQ(verify(r).verdict, Verdict::ok);
  // Found with --level when it is elsewhere; refused by name when it is nowhere.
  ReplayOptions elsewhere;
  elsewhere.level = levelPath("arena.tmj");
  EXPECT_EQ(verify(r, elsewhere).verdict, Verdict::ok);
  std::filesystem::rename(dir.file("arena.tmj"), dir.file("moved.tmj"));
  try {
    verify(r);
    ADD_FAILURE() << "a missing level was accepted";
  } catch (const game::RecordingError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": its level 'arena.tmj' is not at " +
                                         dir.file("arena.tmj") + " (give it with --level)");
  }
  // One crate's health edited: another level.
  std::ifstream in(dir.file("moved.tmj"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = text.find("\"name\": \"health\"");
  ASSERT_NE(at, std::string::npos);
  const std::size_t value = text.find("\"value\": ", at);
  ASSERT_NE(value, std::string::npos);
  text.insert(value + 9, "1");
  std::ofstream(dir.file("arena.tmj")) << text;
  try {
    verify(r);
    ADD_FAILURE() << "a changed level was accepted";
  } catch (const game::RecordingError& e) {
    EXPECT_NE(std::string(e.what()).find("is not the one recorded (content hash "),
              std::string::npos)
        << e.what();
  }
}

// Cut at every byte: the file reads up to its last whole chunk (a cut inside the header is a
// refusal), never further; a sample of cuts replays and verifies up to there.
TEST(Session, TruncationAtEveryByte) {
  const ScratchDir dir;
  const std::string path = dir.file("cut.rec");
  RecordSpec spec;
  spec.bots = 2;
  spec.ticks = 240;
  spec.keyframeEvery = 60;
  record(path, spec);
  const std::vector<std::uint8_t> bytes = bytesOf(path);
  const game::RecordingContents whole = game::readRecording(bytes, path);
  const std::size_t headerEnd = whole.chunks[1].offset;
  std::int64_t lastTicks = 0;
  for (std::size_t cut = 0; cut < bytes.size(); ++cut) {
    const std::span<const std::uint8_t> part = std::span(bytes).first(cut);
    if (cut < headerEnd) {
      EXPECT_THROW(game::parseRecording(part, path), game::RecordingError) << cut;
      continue;
    }
    const Recording r = game::parseRecording(part, path);
    ASSERT_FALSE(r.finished) << cut;
    EXPECT_GE(r.ticks, lastTicks) << cut;  // more file, never fewer ticks
    lastTicks = r.ticks;
    // A cut inside a chunk is named; a cut between chunks reads clean but unfinished.
    bool atBoundary = false;
    for (const game::RecordingChunk& c : whole.chunks)
      atBoundary = atBoundary || c.offset == cut;
    EXPECT_EQ(r.damage.has_value(), !atBoundary) << cut;
    if (r.damage) {
      EXPECT_NE(r.damage->find("truncated"), std::string::npos) << *r.damage;
    }
    if (cut % 211 == 0) {
      const ReplayReport report = verify(r);
      EXPECT_EQ(report.verdict, Verdict::damaged) << cut << ": " << report.message;
      EXPECT_EQ(report.end, r.ticks);
    }
  }
  EXPECT_EQ(lastTicks, 240);
}

// A flipped bit anywhere after the header is caught by its chunk's CRC: reading stops at that
// chunk and names it; what came before replays.
TEST(Session, BitFlipsAreNamedByTheirChunk) {
  const ScratchDir dir;
  const std::string path = dir.file("flip.rec");
  RecordSpec spec;
  spec.bots = 2;
  spec.ticks = 180;
  spec.keyframeEvery = 60;
  record(path, spec);
  const std::vector<std::uint8_t> bytes = bytesOf(path);
  const game::RecordingContents whole = game::readRecording(bytes, path);
  rc::Random rng(3);
  for (std::size_t at = whole.chunks[1].offset; at < bytes.size(); at += 1 + rng.below(13)) {
    std::vector<std::uint8_t> bad = bytes;
    bad[at] ^= static_cast<std::uint8_t>(1u << rng.below(8));
    const Recording r = game::parseRecording(bad, path);
    std::size_t chunk = 0;
    while (chunk + 1 < whole.chunks.size() && whole.chunks[chunk + 1].offset <= at)
      ++chunk;
    ASSERT_TRUE(r.damage.has_value()) << at;
    const std::string name = "chunk " + std::to_string(chunk) + " at byte " +
                             std::to_string(whole.chunks[chunk].offset) + ": ";
    EXPECT_EQ(r.damage->rfind(name, 0), 0u) << at << ": " << *r.damage;
    EXPECT_EQ(r.chunks, chunk) << at;
  }
  // One replayed: it verifies up to the damage.
  std::vector<std::uint8_t> bad = bytes;
  bad[whole.chunks[6].offset + 20] ^= 4;
  const ReplayReport report = verify(game::parseRecording(bad, path));
  EXPECT_EQ(report.verdict, Verdict::damaged) << report.message;
  EXPECT_GT(report.hashesChecked, 0);
}

// Chunks with right CRCs that claim what no recording holds: 2^32-1 ticks of inputs, an END
// that says 2^40 ticks, inputs that skip ahead, a keyframe of 4 GiB.
TEST(Session, ForgedChunksAreDamageNotAllocations) {
  const ScratchDir dir;
  const std::string good = dir.file("good.rec");
  RecordSpec spec;
  spec.bots = 2;
  spec.ticks = 180;
  spec.keyframeEvery = 60;
  record(good, spec);
  auto forged = [&](std::uint32_t type, std::size_t offset, std::uint64_t value, int bytes) {
    rewrite(good, dir.file("forged.rec"),
            [&](std::size_t, std::uint32_t t, std::vector<std::uint8_t>& p) {
              if (t != type) return;
              for (int k = 0; k < bytes; ++k)
                p[offset + static_cast<std::size_t>(k)] =
                    static_cast<std::uint8_t>(value >> (8 * k));
            });
    return game::loadRecording(dir.file("forged.rec"));
  };
  const Recording a = forged(game::kChunkInputs, 8, 0xFFFFFFFFu, 4);
  ASSERT_TRUE(a.damage);
  EXPECT_NE(a.damage->find("it holds 4294967295 ticks, not 1 to 60"), std::string::npos)
      << *a.damage;
  const Recording b = forged(game::kChunkEnd, 0, std::uint64_t{1} << 40, 8);
  ASSERT_TRUE(b.damage);
  EXPECT_NE(b.damage->find("it says 1099511627776 ticks, the inputs hold 180"), std::string::npos)
      << *b.damage;
  EXPECT_EQ(b.ticks, 180);
  const Recording c = forged(game::kChunkInputs, 0, 1000, 8);
  ASSERT_TRUE(c.damage);
  EXPECT_NE(c.damage->find("its inputs start at tick 1000, expected 0"), std::string::npos);
  const Recording d = forged(game::kChunkKeyframe, 16, 0xFFFFFFFFu, 4);
  ASSERT_TRUE(d.damage);
  EXPECT_NE(d.damage->find("a keyframe of 4294967295 bytes"), std::string::npos) << *d.damage;
}

TEST(Session, ReplayNeverChangesItsInput) {
  const ScratchDir dir;
  const std::string path = dir.file("same.rec");
  record(path, RecordSpec{});
  const std::vector<std::uint8_t> before = bytesOf(path);
  const auto stamp = std::filesystem::last_write_time(path);
  ReplayOptions options;
  options.synctest = true;
  options.to = 120;
  verify(game::loadRecording(path), options);
  std::FILE* sink = std::tmpfile();
  game::runBatch(dir.path().string(), {}, sink);
  std::fclose(sink);
  EXPECT_EQ(bytesOf(path), before);
  EXPECT_EQ(std::filesystem::last_write_time(path), stamp);
}

std::vector<std::string> linesOf(std::FILE* f) {
  std::rewind(f);
  std::vector<std::string> lines;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, f) != nullptr) {
    std::string line(buffer);
    // Times differ run to run; the rest must not.
    const std::size_t s = line.find("\"seconds\": ");
    if (s != std::string::npos) line.erase(s, line.find(',', s) - s);
    lines.push_back(line);
  }
  return lines;
}

// Shards 0/n ... n-1/n cover the list once between them, and threads change nothing but times.
TEST(Session, BatchShardsAreDisjointAndThreadsChangeNothing) {
  std::vector<std::string> files;
  for (int k = 0; k < 11; ++k)
    files.push_back("s" + std::to_string(k) + ".rec");
  for (int n = 1; n <= 5; ++n) {
    std::vector<std::string> all;
    for (int i = 0; i < n; ++i)
      for (const std::string& f : game::shardOf(files, {i, n}))
        all.push_back(f);
    std::sort(all.begin(), all.end());
    std::vector<std::string> sorted = files;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(all, sorted) << n;
  }
  EXPECT_FALSE(game::parseShard("3/3"));
  EXPECT_FALSE(game::parseShard("1/0"));
  EXPECT_FALSE(game::parseShard("-1/2"));
  EXPECT_FALSE(game::parseShard("1/2x"));
  ASSERT_TRUE(game::parseShard("2/4"));

  const ScratchDir dir;
  for (int k = 0; k < 4; ++k) {
    RecordSpec spec;
    spec.seed = static_cast<std::uint64_t>(k + 1);
    spec.ticks = 180;
    spec.bots = 4;
    record(dir.file("s" + std::to_string(k) + ".rec"), spec);
  }
  dir.write("broken.rec", "RICOCHET");
  game::BatchOptions one, two;
  two.jobs = 2;
  std::FILE* a = std::tmpfile();
  std::FILE* b = std::tmpfile();
  EXPECT_EQ(game::runBatch(dir.path().string(), one, a), 1);  // broken.rec cannot be replayed
  EXPECT_EQ(game::runBatch(dir.path().string(), two, b), 1);
  const std::vector<std::string> linesA = linesOf(a), linesB = linesOf(b);
  std::fclose(a);
  std::fclose(b);
  ASSERT_EQ(linesA.size(), 5u);
  EXPECT_EQ(linesA, linesB);
  EXPECT_NE(linesA[0].find("broken.rec\", \"verdict\": \"error\""), std::string::npos) << linesA[0];
  EXPECT_NE(linesA[1].find("\"verdict\": \"ok\""), std::string::npos) << linesA[1];
}

}  // namespace session_test
