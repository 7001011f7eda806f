// The process's scratch folder, <tmp>/shadowlab-<pid>, where plugin libraries are copied before
// dlopen (see plugin_library.h). It exists only while something is in it is needed:
//   - created on first use, which also removes the folders of processes that are gone (a killed
//     run cannot clean up after itself);
//   - removed at exit, and on SIGINT, SIGTERM and SIGHUP (the signal is then re-raised, so the
//     exit status still says what happened). The shadowlab executable catches SIGINT itself
//     (util/progress.h: a command stops cleanly and exits, which removes the folder); a second
//     SIGINT removes it here before the process dies.
// A live process holds an flock on <folder>/.lock; a folder whose lock can be taken belongs to
// nobody, whatever its pid says (pids are reused, and other pid namespaces share /tmp).
#pragma once

#include <filesystem>
#include <string>

namespace shadowlab {

// The folder, created if needed; empty (with `error` set) when it cannot be created.
std::filesystem::path scratchDir(std::string& error);
// Removes the folder now (it is created again on next use). Also what exit and the signals do.
void removeScratchDir();
// Removes <tmp>/shadowlab-<pid> folders nobody holds; returns how many. Called by scratchDir().
int removeStaleScratchDirs(const std::filesystem::path& tmp);

} // namespace shadowlab
