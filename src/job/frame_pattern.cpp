#include "strahl/job/frame_pattern.h"

#include "strahl/core/error.h"

namespace strahl {

bool hasFramePattern(const std::string& name) { return name.find('#') != std::string::npos; }

std::string expandFramePattern(const std::string& name, int frame) {
    const std::string digits = std::to_string(frame);
    std::string out;
    for (size_t i = 0; i < name.size();) {
        if (name[i] != '#') {
            out += name[i++];
            continue;
        }
        size_t run = 0;
        while (i < name.size() && name[i] == '#') ++run, ++i;
        if (digits.size() < run) out.append(run - digits.size(), '0');
        out += digits;
    }
    return out;
}

std::filesystem::path expandFramePattern(const std::filesystem::path& path, int frame,
                                         const std::string& what) {
    const std::string name = path.string();
    if (!hasFramePattern(name)) return path;
    if (frame < 0)
        fail(what, " ", name, ": the name has a '#' frame pattern but no --frame N was given");
    return expandFramePattern(name, frame);
}

}  // namespace strahl
