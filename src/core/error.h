// One error style for the whole code base (see CODE_STYLE.md "Errors").
//
// * User errors (bad file, bad parameter) throw penumbra::Error carrying the file or
//   parameter they concern; main() prints exactly one line "penumbra: <where>: <what>" and
//   exits non-zero. Error::exitCode() says which code (1 error, 2 usage, 77 no GL context).
// * Programmer errors use PENUMBRA_CHECK, which stays on in release builds and aborts with
//   the source location.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace penumbra {

enum class ExitCode : int { Ok = 0, Error = 1, Usage = 2, ThresholdExceeded = 3, NoContext = 77 };

// `text` with its control characters (below 0x20, and 0x7f) escaped: \n, \r, \t, else \xNN.
std::string escapeControls(const std::string& text);

// A value a message quotes, at most `limit` characters of it (a bad string may be a megabyte):
// the value when short enough, else its first characters (whole UTF-8 sequences), "...", and
// how long it was.
std::string abbreviate(const std::string& value, std::size_t limit = 80);

// The longest message an Error carries (abbreviated past it): one line a terminal can show.
inline constexpr std::size_t kMaxErrorMessage = 2000;

class Error : public std::runtime_error {
 public:
  // `where` is the file, field or object the problem concerns ("scenes/a.json", "samples",
  // "param", "light[2]": a field's own name; the CLI shows the flag that sets it); `what` says the problem in a few
  // words. The message is one line whatever the two hold (a file name or a JSON key may hold a newline): control
  // characters are written escaped, as `\n`, `\t` or `\x1b`; past kMaxErrorMessage characters it is abbreviated.
  Error(std::string where, const std::string& what, ExitCode code = ExitCode::Error)
      : std::runtime_error(abbreviate(escapeControls(where.empty() ? what : where + ": " + what), kMaxErrorMessage)),
        where_(std::move(where)),
        detail_(what),
        code_(code) {}
  const std::string& where() const { return where_; }
  const std::string& detail() const { return detail_; }  // `what`, without `where`
  ExitCode exitCode() const { return code_; }

 private:
  std::string where_, detail_;
  ExitCode code_;
};

// Why `path` cannot be read as an input file, or "" when it is a regular file: "no such file",
// "is a folder, not a file", "is not a regular file (a device, socket or pipe)", or the system's
// reason ("permission denied" on a folder above it). Every loader words a bad path the same way.
std::string fileProblem(const std::string& path);

[[noreturn]] void checkFailed(const char* expr, const char* file, int line, const std::string& msg);

}  // namespace penumbra

#define PENUMBRA_CHECK(cond, msg)                                           \
  do {                                                                      \
    if (!(cond)) ::penumbra::checkFailed(#cond, __FILE__, __LINE__, (msg)); \
  } while (0)
