// Animated images and videos through the ffmpeg program (see video_export.h).
#include "util/video_export.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

extern char** environ;

namespace shadowlab {

std::filesystem::path findFfmpeg() {
    const char* path = std::getenv("PATH");
    std::stringstream folders(path ? path : "");
    for (std::string folder; std::getline(folders, folder, ':');) {
        const std::filesystem::path candidate = std::filesystem::path(folder.empty() ? "." : folder) / "ffmpeg";
        if (::access(candidate.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(candidate)) return candidate;
    }
    return {};
}

std::string exportProblem(const std::string& option, const std::filesystem::path& file) {
    const std::string extension = file.extension().string();
    if (extension != ".gif" && extension != ".mp4" && extension != ".webm")
        return option + " " + file.string() + ": expected a .gif, .mp4 or .webm file (the extension picks the format)";
    if (findFfmpeg().empty())
        return option + " " + file.string() + ": needs the ffmpeg program to encode the frames, and none is on PATH "
               "(Debian: apt-get install ffmpeg)";
    return {};
}

bool encodeFrames(const std::filesystem::path& folder, int fps, const std::filesystem::path& out, std::string& error) {
    const std::filesystem::path ffmpeg = findFfmpeg();
    if (ffmpeg.empty()) {
        error = out.string() + ": the ffmpeg program is not on PATH (Debian: apt-get install ffmpeg)";
        return false;
    }
    const std::string extension = out.extension().string();
    // A GIF gets a palette made from its own frames (ffmpeg's default palette bands the shadows);
    // H.264 needs even sizes and yuv420p for most players.
    const std::string filter = extension == ".gif" ? "split[a][b];[a]palettegen=stats_mode=diff[p];[b][p]paletteuse"
                                                   : "pad=ceil(iw/2)*2:ceil(ih/2)*2";
    std::vector<std::string> args = {ffmpeg.string(), "-nostdin", "-loglevel", "error", "-y", "-framerate", std::to_string(fps),
                                     "-i", (folder / "frame_%05d.png").string(), "-vf", filter};
    if (extension == ".mp4") args.insert(args.end(), {"-c:v", "libx264", "-pix_fmt", "yuv420p"});
    if (extension == ".webm") args.insert(args.end(), {"-c:v", "libvpx-vp9", "-pix_fmt", "yuv420p"});
    if (extension == ".gif") args.insert(args.end(), {"-loop", "0"});
    args.push_back(out.string());
    const std::filesystem::path log = folder / "ffmpeg.log";
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    std::vector<char*> argv;
    for (std::string& arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);
    pid_t child = 0;
    const int spawned = posix_spawn(&child, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    int status = 0;
    if (spawned != 0 || ::waitpid(child, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::ifstream messages(log);
        std::stringstream text;
        text << messages.rdbuf();
        error = out.string() + ": ffmpeg failed" + (text.str().empty() ? std::string() : ": " + text.str());
        while (!error.empty() && (error.back() == '\n' || error.back() == '\r')) error.pop_back();
        return false;
    }
    return true;
}

} // namespace shadowlab
