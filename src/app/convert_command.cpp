// `strahl convert`: a scene in another renderer's format (a Mitsuba 3 .xml, a pbrt-v4 .pbrt)
// written as the strahl JSON scene it imports as, so a user can read and edit
// what the importer understood (docs/cli.md#strahl-convert). Rendering the
// written file gives the same image, bit for bit, as rendering the original.

#include <cstdio>

#include "commands.h"
#include "scene_loading.h"
#include "strahl/core/error.h"
#include "strahl/film/image_output.h"

namespace strahl::app {

int runConvert(const Options& o) {
    const std::filesystem::path out = o.convertOutput;
    const std::filesystem::path folder = out.parent_path().empty() ? "." : out.parent_path();
    std::error_code ec;
    if (!std::filesystem::is_directory(folder, ec))
        fail(out.string(), ": cannot write: folder '", folder.string(), "' does not exist");
    const SceneDocument document = patchedScene(o);
    document.parse();  // what would not render is an error now, not when it is rendered
    writeTextFileAtomically(out, document.textFor(out));
    if (!o.quiet) std::fprintf(stderr, "wrote %s\n", out.string().c_str());
    return 0;
}

}  // namespace strahl::app
