// The scratch folder (see scratch_dir.h).
#include "util/scratch_dir.h"
#include "util/progress.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <system_error>

namespace shadowlab {
namespace {

constexpr const char* kPrefix = "shadowlab-";
constexpr const char* kLockName = ".lock";
// A folder younger than this is never taken for stale: its owner may be between mkdir and flock.
constexpr auto kMinimumStaleAge = std::chrono::seconds(10);

std::mutex mutex;
std::filesystem::path current;   // empty while there is no folder
int lockFd = -1;
// The same path for the signal handler, which may not allocate.
char signalPath[PATH_MAX] = {};
bool hooksInstalled = false;
bool staleRemoved = false;

// Async-signal-safe: raw syscalls only (getdents64 through syscall(), since readdir may allocate).
void removeFolderFromSignal(const char* path) {
    const int dir = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir >= 0) {
        alignas(8) char buffer[4096];
        for (;;) {
            const long bytes = ::syscall(SYS_getdents64, dir, buffer, sizeof(buffer));
            if (bytes <= 0) break;
            bool removedAny = false;
            for (long offset = 0; offset < bytes;) {
                // struct linux_dirent64: ino (8), off (8), reclen (2), type (1), name
                unsigned short length = 0;
                std::memcpy(&length, buffer + offset + 16, sizeof(length));
                const char* name = buffer + offset + 19;
                if (std::strcmp(name, ".") != 0 && std::strcmp(name, "..") != 0)
                    removedAny |= ::unlinkat(dir, name, 0) == 0;
                if (length == 0) break;
                offset += length;
            }
            if (!removedAny) break;   // only what cannot be removed is left
            ::lseek(dir, 0, SEEK_SET);
        }
        ::close(dir);
    }
    ::rmdir(path);
}

void onSignal(int signal) {
    if (signalPath[0]) removeFolderFromSignal(signalPath);
    ::signal(signal, SIG_DFL);
    ::raise(signal);
}

void installHooks() {
    if (hooksInstalled) return;
    hooksInstalled = true;
    std::atexit(removeScratchDir);
    // SIGINT is main()'s (util/progress.h: the first stops cleanly, and exit removes the folder);
    // the second kills at once, after this.
    setHardInterruptHook([] {
        if (signalPath[0]) removeFolderFromSignal(signalPath);
    });
    for (int signal : {SIGINT, SIGTERM, SIGHUP}) {
        struct sigaction previous {};
        if (::sigaction(signal, nullptr, &previous) != 0 || previous.sa_handler != SIG_DFL) continue;   // someone else's
        struct sigaction action {};
        action.sa_handler = onSignal;
        sigemptyset(&action.sa_mask);
        ::sigaction(signal, &action, nullptr);
    }
}

// "shadowlab-123" or "shadowlab-123-2": the pid, else 0.
long pidOfName(const std::string& name) {
    if (name.rfind(kPrefix, 0) != 0) return 0;
    const std::string rest = name.substr(std::strlen(kPrefix));
    size_t digits = 0;
    while (digits < rest.size() && rest[digits] >= '0' && rest[digits] <= '9') ++digits;
    if (digits == 0 || digits > 9) return 0;
    if (digits < rest.size()) {
        if (rest[digits] != '-' || digits + 1 == rest.size()) return 0;
        for (size_t i = digits + 1; i < rest.size(); ++i)
            if (rest[i] < '0' || rest[i] > '9') return 0;
    }
    return std::atol(rest.substr(0, digits).c_str());
}

// Nobody holds the folder: its lock can be taken, or it has none and its process is gone.
bool isStale(const std::filesystem::path& dir, long pid) {
    struct stat info {};
    if (::lstat(dir.c_str(), &info) != 0 || !S_ISDIR(info.st_mode) || info.st_uid != ::getuid()) return false;
    const auto age = std::chrono::system_clock::now() - std::chrono::system_clock::from_time_t(info.st_mtime);
    if (age < kMinimumStaleAge) return false;
    const int fd = ::open((dir / kLockName).c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0) return ::kill(pid_t(pid), 0) != 0 && errno == ESRCH;
    const bool free = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
    ::close(fd);   // releases the lock again
    return free;
}

} // namespace

int removeStaleScratchDirs(const std::filesystem::path& tmp) {
    int removed = 0;
    std::error_code ec;
    for (std::filesystem::directory_iterator it(tmp, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        const long pid = pidOfName(name);
        if (pid <= 0 || it->path() == current) continue;
        if (!isStale(it->path(), pid)) continue;
        std::error_code removeError;
        if (std::filesystem::remove_all(it->path(), removeError) > 0 && !removeError) ++removed;
    }
    return removed;
}

std::filesystem::path scratchDir(std::string& error) {
    std::lock_guard<std::mutex> lock(mutex);
    std::error_code ec;
    if (!current.empty() && std::filesystem::is_directory(current, ec)) return current;
    const std::filesystem::path tmp = std::filesystem::temp_directory_path(ec);
    if (ec) {
        error = "no temporary folder (" + ec.message() + ")";
        return {};
    }
    if (!staleRemoved) {
        staleRemoved = true;
        removeStaleScratchDirs(tmp);
    }
    if (lockFd >= 0) ::close(lockFd);
    lockFd = -1;
    current.clear();
    // Normally shadowlab-<pid>; a suffix when another live process (another pid namespace) has it.
    for (int attempt = 0; attempt < 100 && current.empty(); ++attempt) {
        std::string name = kPrefix + std::to_string(::getpid());
        if (attempt > 0) name += "-" + std::to_string(attempt);
        const std::filesystem::path dir = tmp / name;
        std::filesystem::create_directory(dir, ec);
        if (ec || std::filesystem::is_symlink(dir, ec)) continue;
        const int fd = ::open((dir / kLockName).c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0600);
        if (fd < 0) continue;
        if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
            ::close(fd);
            continue;
        }
        lockFd = fd;
        current = dir;
    }
    if (current.empty()) {
        error = "cannot create a scratch folder in " + tmp.string();
        return {};
    }
    const std::string path = current.string();
    if (path.size() < sizeof(signalPath)) std::memcpy(signalPath, path.c_str(), path.size() + 1);
    installHooks();
    return current;
}

void removeScratchDir() {
    std::lock_guard<std::mutex> lock(mutex);
    signalPath[0] = '\0';
    if (current.empty()) return;
    std::error_code ec;
    std::filesystem::remove_all(current, ec);
    if (lockFd >= 0) ::close(lockFd);
    lockFd = -1;
    current.clear();
}

} // namespace shadowlab
