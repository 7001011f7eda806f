// Host log implementation: stderr plus a bounded ring for the UI.
#include "util/log.h"

#include <cstdio>

#include "util/strings.h"

namespace shadowlab {
namespace {
std::mutex gLogMutex;
std::deque<LogEntry> gLogRing;
bool gQuiet = false;
constexpr size_t kLogRingSize = 200;
} // namespace

void logMessage(LogLevel level, const std::string& raw) {
    // Messages quote files and options: a NUL byte would end the line early on stderr and in the
    // UI, a carriage return or escape sequence would garble it. One place makes them printable.
    const std::string message = printable(raw, true);
    std::lock_guard lock(gLogMutex);
    if (level != LogLevel::Info || !gQuiet) {
        const char* prefix = level == LogLevel::Error ? "error: " : level == LogLevel::Warning ? "warning: " : "";
        std::fprintf(stderr, "%s%s\n", prefix, message.c_str());
    }
    gLogRing.push_back({level, message});
    if (gLogRing.size() > kLogRingSize) gLogRing.pop_front();
}

void setLogQuiet(bool quiet) {
    std::lock_guard lock(gLogMutex);
    gQuiet = quiet;
}

bool logQuiet() {
    std::lock_guard lock(gLogMutex);
    return gQuiet;
}

std::deque<LogEntry> recentLog() {
    std::lock_guard lock(gLogMutex);
    return gLogRing;
}

} // namespace shadowlab
