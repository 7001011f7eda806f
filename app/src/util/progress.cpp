// Progress of long phases and the Ctrl-C flag (see progress.h).
#include "util/progress.h"

#include <signal.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "util/log.h"
#include "util/strings.h"

namespace shadowlab {
namespace {

volatile sig_atomic_t gInterrupted = 0;
void (*gHardInterruptHook)() = nullptr;

// Async-signal-safe: a flag, write(2), and for the second signal the default action.
void onInterrupt(int) {
    if (gInterrupted) {
        if (gHardInterruptHook) gHardInterruptHook();
        ::signal(SIGINT, SIG_DFL);
        ::raise(SIGINT);
        return;
    }
    gInterrupted = 1;
    static const char note[] = "\nshadowlab: interrupted: stopping after the current frame and writing what is done "
                               "(Ctrl-C again stops at once)\n";
    const ssize_t ignored = ::write(STDERR_FILENO, note, sizeof(note) - 1);
    (void)ignored;
}

} // namespace

void catchInterrupts() {
    struct sigaction action {};
    action.sa_handler = onInterrupt;
    sigemptyset(&action.sa_mask);
    ::sigaction(SIGINT, &action, nullptr);
}

void setHardInterruptHook(void (*hook)()) { gHardInterruptHook = hook; }

bool interrupted() { return gInterrupted != 0; }
void requestInterrupt() { gInterrupted = 1; }
void clearInterrupt() { gInterrupted = 0; }

std::string durationText(double seconds) {
    char text[32];
    if (seconds < 90.0) std::snprintf(text, sizeof(text), "%.0f s", seconds);
    else if (seconds < 5400.0) std::snprintf(text, sizeof(text), "%.0f min %02.0f s", std::floor(seconds / 60.0), std::fmod(seconds, 60.0));
    else std::snprintf(text, sizeof(text), "%.1f h", seconds / 3600.0);
    return text;
}

Progress::Progress(std::string what, uint64_t total, std::string unit)
    : what_(std::move(what)), unit_(std::move(unit)), total_(total), start_(std::chrono::steady_clock::now()),
      nextPrint_(start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(kQuietSeconds))) {}

Progress::~Progress() {
    if (printed_) print(done_, true);   // a long phase says how it ended
}

bool Progress::step(uint64_t done) {
    done_ = done;
    if (interrupted()) return false;
    const auto now = std::chrono::steady_clock::now();
    if (now < nextPrint_) return true;
    nextPrint_ = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(kIntervalSeconds));
    print(done, false);
    return true;
}

void Progress::stepOrThrow(uint64_t done) {
    if (!step(done)) throw Interrupted();
}

void Progress::print(uint64_t done, bool last) {
    if (logQuiet()) return;
    printed_ = true;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::string line = what_ + ": " + std::to_string(done) + " of " + std::to_string(total_) + " " + unit_ + ", " +
                       durationText(elapsed) + " elapsed";
    if (last) line += interrupted() ? ", interrupted" : done >= total_ ? ", done" : ", stopped";
    else if (done > 0 && done < total_) line += ", about " + durationText(elapsed / double(done) * double(total_ - done)) + " left";
    std::fprintf(stderr, "%s\n", printable(line).c_str());
}

} // namespace shadowlab
