// Animated images and videos of a path or a tour step (issue 29): numbered PNG frames encoded by
// the `ffmpeg` program when it is on PATH (Debian package ffmpeg, optional: nothing else needs it).
// The format follows the file's extension: .gif (a palette made from the frames), .mp4 (H.264,
// yuv420p, even sizes) or .webm (VP9).
#pragma once

#include <filesystem>
#include <string>

namespace shadowlab {

// The ffmpeg program on PATH ("" when there is none).
std::filesystem::path findFfmpeg();

// What is wrong with `file` as an export target ("" when fine): its extension, and ffmpeg's
// absence. `option` names the option in the message ("--export out.mp4: ...").
std::string exportProblem(const std::string& option, const std::filesystem::path& file);

// Encodes `folder`/frame_%05d.png at `fps` into `out` (ffmpeg's own messages on failure).
bool encodeFrames(const std::filesystem::path& folder, int fps, const std::filesystem::path& out, std::string& error);

} // namespace shadowlab
