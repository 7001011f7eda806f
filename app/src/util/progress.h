// Long phases and Ctrl-C. Valid input can be slow on llvmpipe (a 4096 x 4096 sphere, a terrain of
// 4096 subdivisions, a path of 65,536 frames, a benchmark spec without "frames" on the forest):
// each long phase reports its progress with an estimate of the time left, and Ctrl-C stops it
// cleanly with what it has done written.
//
//   - Progress: "<what>: 1200 of 4097 rows, 2.1 s elapsed, about 5.1 s left" on stderr, first after
//     kQuietSeconds (short phases print nothing), then at most every kIntervalSeconds, and a last
//     line when it printed any; nothing in quiet mode (-q). Scene generation, path runs, bench,
//     stress and the report use it.
//   - SIGINT (catchInterrupts, installed by main): the first sets a flag that those phases check
//     between frames, rows and mesh rows; they stop, write their partial results (a bench's rows
//     so far, a path's frames so far, the stress cells done) and the command exits with
//     kExitInterrupted (130, as a shell reports a process killed by SIGINT). A phase with
//     nothing partial to keep (generating a scene) throws Interrupted, which main turns into 130.
//     A second Ctrl-C kills at once (the scratch folder is still removed, util/scratch_dir.h).
#pragma once

#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace shadowlab {

constexpr int kExitInterrupted = 130;

// Installs the SIGINT handler (once; main() calls it before anything runs).
void catchInterrupts();
// Whether Ctrl-C was pressed since the start (or since clearInterrupt).
bool interrupted();
// Called by a second Ctrl-C before the process dies of it (async-signal-safe code only: the
// scratch folder's removal, util/scratch_dir.cpp).
void setHardInterruptHook(void (*hook)());
// Raises the flag as SIGINT does (tests), or lowers it again.
void requestInterrupt();
void clearInterrupt();

// Thrown where a phase has no partial result to write; main() exits with kExitInterrupted.
class Interrupted : public std::runtime_error {
public:
    Interrupted() : std::runtime_error("interrupted (Ctrl-C)") {}
};

// "12 s", "3 min 05 s", "1.5 h".
std::string durationText(double seconds);

class Progress {
public:
    static constexpr double kQuietSeconds = 2.0;
    static constexpr double kIntervalSeconds = 2.0;

    // `what` starts every line ("scene forest: objects[1] (terrain)"), `unit` names the steps ("rows").
    Progress(std::string what, uint64_t total, std::string unit);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // `done` of the total finished: prints when due. False once Ctrl-C was pressed (the caller
    // stops and writes what it has); cheap enough to call per mesh row or per frame.
    bool step(uint64_t done);
    // step(), throwing Interrupted instead of returning false.
    void stepOrThrow(uint64_t done);

private:
    void print(uint64_t done, bool last);

    std::string what_, unit_;
    uint64_t total_ = 0, done_ = 0;
    std::chrono::steady_clock::time_point start_, nextPrint_;
    bool printed_ = false;
};

} // namespace shadowlab
