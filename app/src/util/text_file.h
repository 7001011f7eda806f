// Reading and writing files the way every input and output of the program should: only regular
// files are read (a FIFO would block forever, /dev/zero never ends), never more than a stated
// number of bytes, and a write counts as done only once the data has reached the file (a full
// disk or /dev/full is an error, not a silent success). Errors name the file.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace shadowlab {

constexpr size_t kMebibyte = size_t(1) << 20;
// Scene files and benchmark specs are hand-written JSON: a few kilobytes. Anything near this limit
// is not one, and nlohmann holds about ten bytes per byte of input.
constexpr size_t kMaxJsonFileBytes = 16 * kMebibyte;
// Deeper nesting than any scene or spec needs; bounds the memory and recursion a file can cause.
constexpr int kMaxJsonDepth = 64;

// The whole of `file` into `text`. Fails for anything but a regular file (checked on the opened
// file, so a path swapped meanwhile cannot slip through) and for files over `maxBytes`.
bool readRegularFile(const std::filesystem::path& file, size_t maxBytes, std::string& text, std::string& error,
                     const std::string& what = "file");

// Parses JSON, catching everything the parser throws: syntax errors (with line and column), numbers
// beyond a double (1e400), nesting deeper than kMaxJsonDepth. `source` starts every message.
bool parseJsonText(const std::string& text, const std::string& source, nlohmann::json& out, std::string& error);

// readRegularFile (at most kMaxJsonFileBytes) + parseJsonText.
bool readJsonFile(const std::filesystem::path& file, nlohmann::json& out, std::string& error,
                  const std::string& what = "JSON file");

// Writes `bytes` to `file` (its folder created when needed) and checks that every byte was written
// and the file closed cleanly.
bool writeWholeFile(const std::filesystem::path& file, const std::string& bytes, std::string& error);

// Flushes stdout; false when anything written to it was lost (e.g. `> /dev/full`).
bool flushStandardOutput(std::string& error);

} // namespace shadowlab
