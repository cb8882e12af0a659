// A file given to a reader (a scene, a level or tileset, a weapon table, a recording), read whole
// with the guards every reader needs: it must be a regular file (a device such as /dev/zero, or a
// pipe, has no size to check and would be read without end), no larger than the reader's limit
// (checked before reading, and again while reading, so a file that grows meanwhile is refused
// too). Header-only: the scene, level, match and session libraries each use it.
#pragma once

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <istream>
#include <optional>
#include <string>

namespace game {

// A limit as messages show it: "32 MiB", "1 GiB", "512 bytes".
inline std::string byteSizeText(std::uintmax_t bytes) {
  if (bytes >= (1u << 30) && bytes % (1u << 30) == 0) return std::to_string(bytes >> 30) + " GiB";
  if (bytes >= (1u << 20) && bytes % (1u << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  if (bytes >= (1u << 10) && bytes % (1u << 10) == 0) return std::to_string(bytes >> 10) + " KiB";
  return std::to_string(bytes) + " bytes";
}

// Reads the file at `path` into `out` (a std::string or a std::vector<std::uint8_t>). Nothing,
// or why it cannot be read, for the reader to put after the file's name: "cannot open the file:
// it does not exist", "... it is a directory", "... it is not a regular file", "the file is
// larger than 32 MiB", "cannot read the file".
template <class Bytes>
std::optional<std::string> readInputFile(const std::string& path, std::uintmax_t limit,
                                         Bytes& out) {
  // Opened first, then looked at through the descriptor (not the path, which could be swapped
  // for a pipe in between); O_NONBLOCK so that opening a FIFO never waits for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    if (error == ENOENT) return "cannot open the file: it does not exist";
    return std::string("cannot open the file: ") + std::strerror(error);
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) return std::string("cannot read the file: ") + std::strerror(errno);
  if (S_ISDIR(st.st_mode)) return "cannot open the file: it is a directory";
  if (!S_ISREG(st.st_mode)) return "cannot open the file: it is not a regular file";
  const std::string tooLarge = "the file is larger than " + byteSizeText(limit);
  if (static_cast<std::uintmax_t>(st.st_size) > limit) return tooLarge;
  out.clear();
  out.reserve(static_cast<std::size_t>(st.st_size));
  using Byte = typename Bytes::value_type;
  static_assert(sizeof(Byte) == 1);
  char buffer[1 << 16];
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0) {
      if (errno == EINTR) continue;
      return std::string("cannot read the file: ") + std::strerror(errno);
    }
    if (got == 0) break;
    if (out.size() + static_cast<std::size_t>(got) > limit) return tooLarge;
    const Byte* bytes = reinterpret_cast<const Byte*>(buffer);
    out.insert(out.end(), bytes, bytes + got);
  }
  return std::nullopt;
}

// A line of a text read as a stream (an input script on a pipe, a list of recordings), at most
// `limit` characters: std::getline would take a line of /dev/zero's without end before any check
// of its length. Reads through the newline (dropped); false at the end of the stream. A longer
// line sets `tooLong` and stops there.
inline bool readBoundedLine(std::istream& in, std::string& line, std::size_t limit, bool& tooLong) {
  line.clear();
  tooLong = false;
  bool any = false;
  for (int c = in.get(); c != std::char_traits<char>::eof(); c = in.get()) {
    any = true;
    if (c == '\n') return true;
    if (line.size() == limit) {
      tooLong = true;
      return true;
    }
    line += static_cast<char>(c);
  }
  return any;
}

}  // namespace game
