// Bad maps: each gives exactly one line that starts with the file and says where and what,
// and nothing a file holds makes the reader crash, hang or allocate without bound (truncated
// and byte-flipped copies of the bundled levels, hostile sizes and nesting).
#include <gtest/gtest.h>
#include <zlib.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "game/level/level_loader.h"
#include "game/level/tiled_reader.h"
#include "game/quote.h"
#include "level_test_support.h"
#include "physics/random.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace level_errors_test {

using json = nlohmann::json;
using level_test::levelErrorOf;
using level_test::ScratchDir;

// A small valid map: 4 x 3 tiles, an embedded tileset whose tile 0 is solid, a CSV wall
// layer, an object layer with a rectangle and a player spawn.
json baseMap() {
  return json::parse(R"({
    "type": "map", "orientation": "orthogonal", "infinite": false,
    "width": 4, "height": 3, "tilewidth": 32, "tileheight": 32,
    "tilesets": [{"firstgid": 1, "name": "t", "tilewidth": 32, "tileheight": 32, "tilecount": 2,
                  "tiles": [{"id": 0, "properties": [{"name": "solid", "type": "bool", "value": true}]}]}],
    "layers": [
      {"id": 1, "name": "walls", "type": "tilelayer", "width": 4, "height": 3,
       "data": [1, 1, 1, 1, 1, 0, 0, 1, 1, 1, 1, 1]},
      {"id": 2, "name": "objects", "type": "objectgroup", "objects": [
        {"id": 1, "x": 40, "y": 40, "width": 16, "height": 16},
        {"id": 2, "type": "player", "point": true, "x": 70, "y": 50}]}
    ]})");
}

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = bytes[i] << 16 | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
                            (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += abc[n >> 18 & 63];
    out += abc[n >> 12 & 63];
    out += i + 1 < bytes.size() ? abc[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? abc[n & 63] : '=';
  }
  return out;
}

std::vector<std::uint8_t> gidBytes(const std::vector<std::uint32_t>& gids) {
  std::vector<std::uint8_t> out;
  for (const std::uint32_t g : gids)
    for (int k = 0; k < 4; ++k)
      out.push_back(static_cast<std::uint8_t>(g >> (8 * k)));
  return out;
}

std::vector<std::uint8_t> zlibbed(const std::vector<std::uint8_t>& bytes) {
  uLongf size = compressBound(static_cast<uLong>(bytes.size()));
  std::vector<std::uint8_t> out(size);
  EXPECT_EQ(compress(out.data(), &size, bytes.data(), static_cast<uLong>(bytes.size())), Z_OK);
  out.resize(size);
  return out;
}

const std::vector<std::uint32_t> kWallGids = {1, 1, 1, 1, 1, 0, 0, 1, 1, 1, 1, 1};

class BadMap : public ::testing::Test {
 protected:
  // Writes the map, loads it, and checks the one-line message names the file and holds every
  // fragment; returns it.
  std::string errorOf(const json& map, std::initializer_list<const char*> fragments,
                      const std::string& name = "bad.tmj") {
    return errorOfText(map.dump(), fragments, name);
  }
  std::string errorOfText(const std::string& text, std::initializer_list<const char*> fragments,
                          const std::string& name = "bad.tmj") {
    const std::string path = dir.write(name, text);
    const std::string message = levelErrorOf([&] { game::loadLevel(path); });
    expectOneLine(message, path);
    for (const char* f : fragments)
      EXPECT_NE(message.find(f), std::string::npos) << message;
    return message;
  }
  static void expectOneLine(const std::string& message, const std::string& file) {
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind(file + ": ", 0), 0u) << message;
  }
  ScratchDir dir;
};

TEST_F(BadMap, MissingFileOrDirectory) {
  const std::string missing = dir.file("nowhere.tmj");
  const std::string message = levelErrorOf([&] { game::loadLevel(missing); });
  EXPECT_EQ(message, missing + ": cannot open the file: it does not exist");
  const std::string directory = dir.path().string();
  EXPECT_EQ(levelErrorOf([&] { game::loadLevel(directory); }),
            directory + ": cannot open the file: it is a directory");
  // A device has no size to check: /dev/zero was read until memory ran out, as a map and as a
  // tileset.
  EXPECT_EQ(levelErrorOf([&] { game::loadLevel("/dev/zero"); }),
            "/dev/zero: cannot open the file: it is not a regular file");
  json m = baseMap();
  m["tilesets"][0] = {{"firstgid", 1}, {"source", "/dev/zero"}};
  EXPECT_EQ(levelErrorOf([&] { game::loadLevel(dir.write("zero.tmj", m.dump())); }),
            "/dev/zero: cannot open the file: it is not a regular file");
}

TEST_F(BadMap, DuplicateKeys) {
  // nlohmann keeps the last of a key given twice: a map's second 'width' silently won.
  std::string text = baseMap().dump();
  text.insert(1, "\"width\": 9, ");
  errorOfText(text, {"bad.tmj: the key 'width' appears twice in one object"});
  // Inside a nested object, in an external tileset (named by its file), and a key of control
  // characters (escaped: the message stays one line).
  json m = baseMap();
  std::string objects = m.dump();
  const std::size_t at = objects.find("\"x\":40");
  ASSERT_NE(at, std::string::npos);
  objects.insert(at, "\"x\": 41, ");
  errorOfText(objects, {"bad.tmj: the key 'x' appears twice in one object"});
  dir.write("twice.tsj",
            R"({"type": "tileset", "name": "t", "name": "u", "tilewidth": 32, "tileheight": 32,)"
            R"( "tilecount": 1})");
  m["tilesets"][0] = {{"firstgid", 1}, {"source", "twice.tsj"}};
  EXPECT_EQ(levelErrorOf([&] { game::loadLevel(dir.write("m.tmj", m.dump())); }),
            dir.file("twice.tsj") + ": the key 'name' appears twice in one object");
  text = baseMap().dump();
  text.insert(1, "\"a\\n\\u001b\": 1, \"a\\n\\u001b\": 2, ");
  errorOfText(text, {"bad.tmj: the key 'a\\x0a\\x1b' appears twice in one object"});
  // 200,000 keys in one object (keys Tiled's format does not use are ignored): the check keeps
  // each object's keys in a set, n log n.
  json wide = baseMap();
  for (int i = 0; i < 200000; ++i)
    wide["k" + std::to_string(i)] = 0;
  const std::string widePath = dir.write("wide.tmj", wide.dump());
  const auto start = std::chrono::steady_clock::now();
  EXPECT_NO_THROW(game::loadLevel(widePath));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

TEST_F(BadMap, InvalidJson) {
  errorOfText("{\"width\": 4,", {"not valid JSON at line 1, column 13"});
  errorOfText("", {"not valid JSON"});
  errorOfText("[1, 2]", {"a Tiled map must be a JSON object"});
  json m = baseMap();
  errorOfText(m.dump().insert(20, "\x01"), {"not valid JSON"});
}

TEST_F(BadMap, WrongTypes) {
  json m = baseMap();
  m["width"] = "4";
  errorOf(m, {"'width' must be an integer from 1 to 4096, got \"4\""});
  m = baseMap();
  m["layers"][1]["objects"][0]["x"] = "forty";
  errorOf(m, {"layer 'objects': object 1: 'x' must be a number, got \"forty\""});
  m = baseMap();
  m["layers"] = json::object();
  errorOf(m, {"'layers' must be an array"});
  m = baseMap();
  m["layers"][1]["objects"][0] = 7;
  errorOf(m, {"layer 'objects': object [0] must be a JSON object, got 7"});
  m = baseMap();
  m["layers"][0]["data"][3] = -1;
  errorOf(m, {"layer 'walls': data[3] must be a gid"});
  m = baseMap();
  m["layers"][1]["objects"][0]["properties"] = {
      {{"name", "friction"}, {"type", "string"}, {"value", "low"}}};
  errorOf(m, {"layer 'objects': object 1: property 'friction': must be a float, got a string"});
  m = baseMap();
  m["layers"][1]["objects"][0]["properties"] = {
      {{"name", "friction"}, {"type", "float"}, {"value", -1}}};
  errorOf(m, {"object 1: property 'friction': must be from 0 to 100, got -1"});
  m = baseMap();
  m["layers"][1]["objects"][0]["properties"] = {{{"name", "x"}, {"type", "vector"}, {"value", 1}}};
  errorOf(m, {"object 1: property 'x': unknown property type 'vector'"});
  m = baseMap();
  m["properties"] = {{"pixelsPerMeter", 32}};
  errorOf(m, {"'properties' is in the format of Tiled before 1.2"});
}

TEST_F(BadMap, PolygonThatCannotBeSplit) {
  json m = baseMap();
  // A bow tie: its edges 0 and 2 cross.
  m["layers"][1]["objects"].push_back({{"id", 12},
                                       {"x", 10},
                                       {"y", 10},
                                       {"polygon",
                                        {{{"x", 0}, {"y", 0}},
                                         {{"x", 40}, {"y", 40}},
                                         {{"x", 40}, {"y", 0}},
                                         {{"x", 0}, {"y", 40}}}}});
  errorOf(m,
          {"layer 'objects': object 12: polygon: crosses or touches itself: edges 0 and 2 meet"});
  m = baseMap();
  m["layers"][1]["objects"].push_back(
      {{"id", 13},
       {"x", 10},
       {"y", 10},
       {"polygon", {{{"x", 0}, {"y", 0}}, {{"x", 40}, {"y", 0}}, {{"x", 80}, {"y", 0}}}}});
  errorOf(m, {"object 13: polygon: has no area: its points lie on one line"});
  m = baseMap();
  json many = json::array();
  for (int i = 0; i < 300; ++i)
    many.push_back({{"x", i}, {"y", (i % 2) * 5}});
  many.push_back({{"x", 150}, {"y", 100}});
  m["layers"][1]["objects"].push_back({{"id", 14}, {"x", 0}, {"y", 0}, {"polygon", many}});
  errorOf(m, {"object 14: polygon: has 301 vertices, more than the 256 that can be split"});
}

TEST_F(BadMap, UnknownLayerKindAndObjectType) {
  json m = baseMap();
  m["layers"][0]["type"] = "hexlayer";
  errorOf(m, {"layer 'walls': unknown layer type 'hexlayer'"});
  m = baseMap();
  m["layers"][1]["objects"][0]["type"] = "crat";
  errorOf(m, {"layer 'objects': object 1: unknown type 'crat' for a rectangle"});
  m = baseMap();
  m["layers"][1]["objects"][0]["template"] = "crate.tx";
  errorOf(m, {"object 1: object templates are not supported"});
  m = baseMap();
  m["layers"][1]["objects"].push_back(
      {{"id", 3}, {"type", "trigger"}, {"polyline", {{{"x", 0}, {"y", 0}}, {{"x", 9}, {"y", 0}}}}});
  errorOf(m, {"object 3: a polyline cannot be a trigger"});
  m = baseMap();
  m["layers"][1]["objects"].push_back(
      {{"id", 3},
       {"type", "trigger"},
       {"x", 0},
       {"y", 0},
       {"width", 32},
       {"height", 32},
       {"properties",
        {{{"name", "action"}, {"type", "string"}, {"value", "hurt"}},
         {{"name", "damagePerSecond"}, {"type", "float"}, {"value", -5}}}}});
  errorOf(m, {"object 3: property 'damagePerSecond': must be from 0 to 1000000, got -5"});
  m = baseMap();
  m["layers"][1]["objects"][1]["type"] = "pickup";
  errorOf(m, {"object 2: a pickup needs a string property 'item'"});
  m = baseMap();
  m["layers"][1]["objects"][0]["width"] = 0;
  errorOf(m, {"object 1: rectangle: has no width or height"});
}

TEST_F(BadMap, Tilesets) {
  json m = baseMap();
  m["tilesets"][0] = {{"firstgid", 1}, {"source", "missing.tsj"}};
  errorOf(m, {"tileset 'missing.tsj': cannot open the tileset file",
              "missing.tsj': it does not exist"});
  m["tilesets"][0] = {{"firstgid", 1}, {"source", "walls.tsx"}};
  errorOf(m, {"tileset 'walls.tsx': XML tilesets are not supported"});
  // An error inside an external tileset names that file.
  dir.write(
      "broken.tsj",
      R"({"type": "tileset", "name": "b", "tilewidth": 32, "tileheight": "32", "tilecount": 1})");
  m["tilesets"][0] = {{"firstgid", 1}, {"source", "broken.tsj"}};
  const std::string message = levelErrorOf([&] { game::loadLevel(dir.write("m.tmj", m.dump())); });
  EXPECT_EQ(message, dir.file("broken.tsj") +
                         ": 'tileheight' must be an integer from 1 to 4096, got \"32\"");
  m = baseMap();
  m["layers"][0]["data"][1] = 99;
  errorOf(m, {"layer 'walls': tile at column 1, row 0: gid 99 belongs to no tileset"});
  m = baseMap();
  m["tilesets"].push_back(m["tilesets"][0]);
  errorOf(m, {"tileset [1]: 'firstgid' 1 is not above the previous tileset's"});
}

TEST_F(BadMap, TileData) {
  json m = baseMap();
  std::vector<std::uint32_t> short11(kWallGids.begin(), kWallGids.end() - 1);
  m["layers"][0]["encoding"] = "base64";
  m["layers"][0]["data"] = base64(gidBytes(short11));
  errorOf(m,
          {"layer 'walls': tile data holds 44 bytes, the layer needs 48 (4 per tile, 12 tiles)"});
  m["layers"][0]["data"] = "AAAA*AAA";
  errorOf(m, {"layer 'walls': base64 data: invalid character at offset 4"});
  m["layers"][0]["compression"] = "zstd";
  m["layers"][0]["data"] = base64(gidBytes(kWallGids));
  errorOf(m, {"layer 'walls': zstd compression is not supported"});
  m["layers"][0]["compression"] = "lz4";
  errorOf(m, {"unknown compression 'lz4'"});
  m["layers"][0]["compression"] = "zlib";
  errorOf(m, {"layer 'walls': zlib data is corrupt"});
  m["layers"][0]["data"] = base64(zlibbed(gidBytes(short11)));
  errorOf(m, {"zlib data decompresses to 44 bytes, the layer needs 48"});
  // A bomb: 16 MiB of zeros in a few kB, where the layer needs 48 bytes.
  m["layers"][0]["data"] = base64(zlibbed(std::vector<std::uint8_t>(16 << 20, 0)));
  errorOf(m, {"zlib data decompresses to more than the layer's 48 bytes"});
  std::vector<std::uint8_t> cut = zlibbed(gidBytes(kWallGids));
  cut.resize(cut.size() - 6);
  m["layers"][0]["data"] = base64(cut);
  errorOf(m, {"zlib data is truncated"});
  m = baseMap();
  m["layers"][0]["data"].push_back(1);
  errorOf(m, {"layer 'walls': 'data' holds 13 tiles, the layer needs 12"});
  m = baseMap();
  m["layers"][0]["encoding"] = "xml";
  errorOf(m, {"unknown encoding 'xml'"});
}

TEST_F(BadMap, UnsupportedMaps) {
  json m = baseMap();
  m["infinite"] = true;
  errorOf(m, {"bad.tmj: infinite maps are not supported"});
  m = baseMap();
  m["orientation"] = "isometric";
  errorOf(m, {"'isometric' maps are not supported, only orthogonal ones"});
  m = baseMap();
  m["layers"][0]["chunks"] = json::array();
  errorOf(m, {"layer 'walls': chunked tile data (an infinite map) is not supported"});
  m = baseMap();
  m["type"] = "tileset";
  errorOf(m, {"this is a tileset, not a map"});
}

TEST_F(BadMap, HostileSizesAndNumbers) {
  json m = baseMap();
  m["width"] = 2147483648u;
  m["height"] = 2147483648u;
  errorOf(m, {"'width' must be an integer from 1 to 4096, got 2147483648"});
  m["width"] = 4096;
  m["height"] = 4096;
  errorOf(m, {"the map is 4096x4096 tiles, more than the 4194304 supported"});
  m = baseMap();
  m["tilewidth"] = 0;
  errorOf(m, {"'tilewidth' must be an integer from 1 to 4096, got 0"});
  errorOfText(R"({"type": "map", "orientation": "orthogonal", "width": 1e999})",
              {"not valid JSON", "number overflow"});
  m = baseMap();
  m["layers"][1]["objects"][0]["x"] = 1e300;
  errorOf(m, {"object 1: 'x' must be a number from"});
  m = baseMap();
  m["properties"] = {{{"name", "pixelsPerMeter"}, {"type", "float"}, {"value", 0}}};
  errorOf(m, {"map: property 'pixelsPerMeter': must be from"});
  // Nesting: arrays inside a property's value, far deeper than any map.
  std::string deep = baseMap().dump();
  deep.insert(deep.size() - 1,
              ", \"extra\": " + std::string(100000, '[') + std::string(100000, ']'));
  errorOfText(deep, {"JSON nested deeper than 64 levels"});
  // A checkerboard of 600 x 600 tiles would be 720,000 chain links: refused before tracing.
  m = baseMap();
  m["width"] = m["height"] = m["layers"][0]["width"] = m["layers"][0]["height"] = 600;
  json board = json::array();
  for (int i = 0; i < 600 * 600; ++i)
    board.push_back(((i / 600) + i) % 2);
  m["layers"][0]["data"] = board;
  errorOf(m, {"layer 'walls': the layer's solid tiles make 720000 shapes, more than the 262144"});
  // Group layers inside group layers.
  m = baseMap();
  json group = m["layers"][1];
  for (int i = 0; i < 20; ++i)
    group = {{"type", "group"}, {"name", "g"}, {"layers", {group}}};
  m["layers"][1] = group;
  errorOf(m, {"group layers nested deeper than 16"});
}

TEST_F(BadMap, NamesFromTheFileStayOnOneLine) {
  json m = baseMap();
  m["layers"][1]["name"] = "two\nlines";
  m["layers"][1]["objects"][0]["type"] = "nope";
  errorOf(m, {"layer 'two\\x0alines': object 1: unknown type"});
}

// The quoting every message uses for text from a file: well-formed UTF-8 kept, control
// characters (C0, DEL, C1) and bytes that are not UTF-8 escaped, a long text cut between
// characters.
TEST(Quote, ControlsAndBytesThatAreNotUtf8AreEscaped) {
  using game::quoteName;
  EXPECT_EQ(quoteName("walls"), "'walls'");
  EXPECT_EQ(quoteName("it's"), "'it\\'s'");
  EXPECT_EQ(quoteName("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"),
            "'caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80'");
  EXPECT_EQ(quoteName("a\nb\x1b[31m\x7f"), "'a\\x0ab\\x1b[31m\\x7f'");
  EXPECT_EQ(quoteName("\xc2\x9b"
                      "1m"),
            "'\\xc2\\x9b1m'");  // C1 CSI as UTF-8
  EXPECT_EQ(quoteName("\x9b"
                      "1m"),
            "'\\x9b1m'");                                              // a lone 8-bit CSI
  EXPECT_EQ(quoteName("\xe2\x82"), "'\\xe2\\x82'");                    // a cut character
  EXPECT_EQ(quoteName("\xed\xa0\x80"), "'\\xed\\xa0\\x80'");           // a surrogate
  EXPECT_EQ(quoteName("\xc0\xaf"), "'\\xc0\\xaf'");                    // an overlong '/'
  EXPECT_EQ(quoteName("\xf4\x90\x80\x80"), "'\\xf4\\x90\\x80\\x80'");  // past U+10FFFF
  std::string accents;
  for (int i = 0; i < 100; ++i)
    accents += "\xc3\xa9";
  EXPECT_EQ(quoteName(accents), "'" + accents.substr(0, 60) + "...'");
  EXPECT_EQ(quoteName("x" + accents), "'x" + accents.substr(0, 58) + "...'");
  EXPECT_FALSE(game::isPlainText(std::string(60, 'k') + "\n\x1b["));
  EXPECT_TRUE(game::isPlainText(std::string(60, 'k')));
}

// Every prefix of a bundled level (a file cut short by a crash or a bad copy) and thousands
// of copies with bytes changed at random: the reader answers each with a level or a
// LevelError, never another exception, a crash or a sanitizer report.
TEST(LevelFuzz, TruncatedAndCorruptedLevelsFailCleanly) {
  ScratchDir dir;
  std::filesystem::copy_file(level_test::levelPath("tiles.tsj"), dir.file("tiles.tsj"));
  std::filesystem::copy_file(level_test::levelPath("tiles.png"), dir.file("tiles.png"));
  std::ifstream in(level_test::levelPath("corridors.tmj"), std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string original = buffer.str();
  int loaded = 0, refused = 0;
  auto attempt = [&](const std::string& text) {
    try {
      game::levelFromMap(game::parseTiledMap(text, "fuzz.tmj", dir.path().string()));
      ++loaded;
    } catch (const game::LevelError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos);
      EXPECT_EQ(what.rfind("fuzz.tmj: ", 0) == 0 || what.find("tiles.tsj: ") != std::string::npos,
                true)
          << what;
      ++refused;
    }
  };
  for (std::size_t n = 0; n < original.size(); n += 13)
    attempt(original.substr(0, n));
  rc::Random random(1912);
  const std::string alphabet = "0123456789-.eE\"[]{},:truefalsn \x01\xff";
  for (int i = 0; i < 3000; ++i) {
    std::string text = original;
    const int edits = 1 + static_cast<int>(random.next() % 4);
    for (int e = 0; e < edits; ++e)
      text[random.next() % text.size()] = alphabet[random.next() % alphabet.size()];
    attempt(text);
  }
  EXPECT_GT(refused, 1000);
  EXPECT_GT(loaded, 10);  // some edits land in names and leave a valid level
}

// What the loader fills in where a property is left out: a spawn's team is its kind's (players
// 0, bots 1), a trigger's damagePerSecond 10.
TEST_F(BadMap, DefaultsWhereAPropertyIsLeftOut) {
  json m = baseMap();
  m["layers"][1]["objects"].push_back(
      {{"id", 3}, {"type", "bot"}, {"point", true}, {"x", 90}, {"y", 50}});
  m["layers"][1]["objects"].push_back(
      {{"id", 4},
       {"type", "bot"},
       {"point", true},
       {"x", 100},
       {"y", 50},
       {"properties", {{{"name", "team"}, {"type", "int"}, {"value", 0}}}}});
  m["layers"][1]["objects"].push_back(
      {{"id", 5},
       {"type", "trigger"},
       {"x", 40},
       {"y", 64},
       {"width", 16},
       {"height", 16},
       {"properties", {{{"name", "action"}, {"type", "string"}, {"value", "hurt"}}}}});
  const game::Level level = game::loadLevel(dir.write("defaults.tmj", m.dump()));
  ASSERT_EQ(level.spawns.size(), 3u);
  EXPECT_EQ(level.spawns[0].team, 0);  // the player
  EXPECT_EQ(level.spawns[1].team, 1);  // a bot without a team
  EXPECT_EQ(level.spawns[2].team, 0);  // a bot on the player's side
  ASSERT_EQ(level.triggers.size(), 1u);
  EXPECT_EQ(level.triggers[0].action, "hurt");
  EXPECT_EQ(level.triggers[0].damagePerSecond, 10.0f);
}

}  // namespace level_errors_test
