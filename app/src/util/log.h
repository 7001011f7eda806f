// Host log: messages go to stderr and to a ring the UI shows, so a failed hot reload or a bad
// parameter is visible in both places.
#pragma once

#include <deque>
#include <mutex>
#include <string>

#include "shadowlab/technique.h"

namespace shadowlab {

struct LogEntry {
    LogLevel level;
    std::string message;
};

void logMessage(LogLevel level, const std::string& message);
inline void logInfo(const std::string& message) { logMessage(LogLevel::Info, message); }
inline void logWarning(const std::string& message) { logMessage(LogLevel::Warning, message); }
inline void logError(const std::string& message) { logMessage(LogLevel::Error, message); }
// Quiet mode drops Info lines on stderr (they still reach the UI ring).
void setLogQuiet(bool quiet);
bool logQuiet();
std::deque<LogEntry> recentLog();

} // namespace shadowlab
