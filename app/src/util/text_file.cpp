// Bounded reads of regular files, JSON parsing that catches everything, checked writes (see text_file.h).
#include "util/text_file.h"
#include "util/strings.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <set>
#include <vector>
#include <system_error>

namespace shadowlab {
namespace {

std::string kindOf(mode_t mode) {
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a plain file";
}

std::string mebibytes(size_t bytes) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.0f MiB", double(bytes) / double(kMebibyte));
    return text;
}

// nlohmann counts bytes up to the offending character; editors want line:column.
std::string lineAndColumn(const std::string& text, size_t byte) {
    const size_t end = std::min(text.size(), byte);
    size_t line = 1, column = 1;
    for (size_t i = 0; i < end; ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return std::to_string(line) + ":" + std::to_string(column);
}

// Offset of the first bracket nested deeper than kMaxJsonDepth, or npos. Strings are skipped
// (with their escapes), so brackets inside them do not count.
size_t tooDeep(const std::string& text) {
    int depth = 0;
    bool inString = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\') ++i;
            else if (c == '"') inString = false;
            continue;
        }
        if (c == '"') inString = true;
        else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth) return i;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return std::string::npos;
}

// A key given twice in one object: nlohmann keeps the last silently, so a typo'd copy of a field
// would override the real one unseen. Thrown from the parser callback, caught in parseJsonText.
struct DuplicateKey {
    std::string pointer, key;
};

// Follows the parser through the document (a stack of open objects and arrays) and throws
// DuplicateKey, with the JSON pointer of the object, at the second occurrence of a key.
class DuplicateKeyCheck {
public:
    bool operator()(int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
        using Event = nlohmann::json::parse_event_t;
        switch (event) {
        case Event::object_start: levels_.push_back({true, {}, {}, 0}); break;
        case Event::array_start: levels_.push_back({false, {}, {}, 0}); break;
        case Event::key: {
            Level& top = levels_.back();
            std::string key = parsed.get<std::string>();
            if (!top.keys.insert(key).second) throw DuplicateKey{pointer(), std::move(key)};
            top.key = std::move(key);
            break;
        }
        case Event::object_end:
        case Event::array_end:
            levels_.pop_back();
            elementDone();
            break;
        case Event::value: elementDone(); break;
        }
        return true;
    }

private:
    struct Level {
        bool object;
        std::set<std::string> keys;
        std::string key;   // the member being read (objects)
        size_t index;      // the element being read (arrays)
    };
    void elementDone() {
        if (!levels_.empty() && !levels_.back().object) ++levels_.back().index;
    }
    // RFC 6901: the innermost level is the object holding the duplicate; the others name the way to it.
    std::string pointer() const {
        std::string out;
        for (size_t i = 0; i + 1 < levels_.size(); ++i) {
            out += '/';
            if (!levels_[i].object) {
                out += std::to_string(levels_[i].index);
                continue;
            }
            for (char c : levels_[i].key) out += c == '~' ? std::string("~0") : c == '/' ? std::string("~1") : std::string(1, c);
        }
        return out;
    }
    std::vector<Level> levels_;
};

} // namespace

bool readRegularFile(const std::filesystem::path& file, size_t maxBytes, std::string& text, std::string& error,
                     const std::string& what) {
    // O_NONBLOCK: opening a FIFO without a writer would otherwise wait forever.
    const int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        error = file.string() + ": cannot open " + what + " (" + std::strerror(errno) + ")";
        return false;
    }
    struct stat info {};
    if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
        error = file.string() + ": cannot read " + what + ": " + kindOf(info.st_mode) + ", not a regular file";
        ::close(fd);
        return false;
    }
    if (info.st_size > 0 && uint64_t(info.st_size) > maxBytes) {
        error = file.string() + ": " + what + " is larger than " + mebibytes(maxBytes) + " (" +
                mebibytes(size_t(info.st_size)) + ")";
        ::close(fd);
        return false;
    }
    text.clear();
    // Files in /proc report size 0: read in chunks, and never past the limit.
    char buffer[1 << 16];
    for (;;) {
        const ssize_t got = ::read(fd, buffer, sizeof(buffer));
        if (got < 0) {
            if (errno == EINTR) continue;
            error = file.string() + ": cannot read " + what + " (" + std::strerror(errno) + ")";
            ::close(fd);
            return false;
        }
        if (got == 0) break;
        if (text.size() + size_t(got) > maxBytes) {
            error = file.string() + ": " + what + " is larger than " + mebibytes(maxBytes);
            ::close(fd);
            return false;
        }
        text.append(buffer, size_t(got));
    }
    ::close(fd);
    return true;
}

bool parseJsonText(const std::string& text, const std::string& source, nlohmann::json& out, std::string& error) {
    if (const size_t at = tooDeep(text); at != std::string::npos) {
        error = source + ":" + lineAndColumn(text, at) + ": JSON nested deeper than " + std::to_string(kMaxJsonDepth) +
                " levels";
        return false;
    }
    try {
        DuplicateKeyCheck check;
        out = nlohmann::json::parse(text, [&check](int depth, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
            return check(depth, event, parsed);
        });
        return true;
    } catch (const DuplicateKey& duplicate) {
        error = source + ": duplicate key " + quoteForMessage(duplicate.key) + " in " +
                (duplicate.pointer.empty() ? std::string("the top-level object") : quoteForMessage(duplicate.pointer)) +
                " (a key may appear once in an object; the reader would otherwise keep the last one silently)";
    } catch (const nlohmann::json::parse_error& e) {
        // Its message starts "[json.exception.parse_error.101] parse error at line 1, column 2: ".
        std::string detail = e.what();
        const size_t colon = detail.find(": ", detail.find("parse error"));
        if (colon != std::string::npos) detail = detail.substr(colon + 2);
        detail = detail.starts_with("syntax error ") ? detail.substr(13) : ": " + detail;
        error = source + ":" + lineAndColumn(text, e.byte > 0 ? e.byte - 1 : 0) + ": JSON syntax error " + detail;
    } catch (const nlohmann::json::exception& e) {
        // out_of_range.406 "number overflow parsing '1e400'" and the like.
        std::string detail = e.what();
        if (const size_t bracket = detail.find("] "); detail.starts_with("[json.exception") && bracket != std::string::npos)
            detail = detail.substr(bracket + 2);
        error = source + ": JSON error: " + detail;
    } catch (const std::bad_alloc&) {
        error = source + ": out of memory while parsing JSON";
    }
    return false;
}

bool readJsonFile(const std::filesystem::path& file, nlohmann::json& out, std::string& error, const std::string& what) {
    std::string text;
    if (!readRegularFile(file, kMaxJsonFileBytes, text, error, what)) return false;
    return parseJsonText(text, file.string(), out, error);
}

bool writeWholeFile(const std::filesystem::path& file, const std::string& bytes, std::string& error) {
    std::error_code ec;
    if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
    std::FILE* out = std::fopen(file.c_str(), "wb");
    if (!out) {
        error = file.string() + ": cannot write (" + std::strerror(errno) + ")";
        return false;
    }
    const size_t written = std::fwrite(bytes.data(), 1, bytes.size(), out);
    int savedErrno = written == bytes.size() ? 0 : errno;
    if (std::fflush(out) != 0 && !savedErrno) savedErrno = errno ? errno : EIO;
    if (std::ferror(out) && !savedErrno) savedErrno = EIO;
    if (std::fclose(out) != 0 && !savedErrno) savedErrno = errno ? errno : EIO;
    if (savedErrno || written != bytes.size()) {
        error = file.string() + ": write failed (" + std::strerror(savedErrno ? savedErrno : EIO) + ")";
        return false;
    }
    return true;
}

bool flushStandardOutput(std::string& error) {
    errno = 0;
    const bool flushed = std::fflush(stdout) == 0;
    if (!flushed || std::ferror(stdout)) {
        // An earlier implicit flush may have failed already, with its errno long gone.
        error = std::string("standard output: write failed") + (errno ? std::string(" (") + std::strerror(errno) + ")" : "") +
                ": some output was lost";
        return false;
    }
    return true;
}

} // namespace shadowlab
