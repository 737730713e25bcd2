#include "image_files.h"

#include <CLI/CLI.hpp>

#include <cctype>
#include <memory>
#include <string>

#include "strahl/film/image_output.h"

namespace strahl::app {

void addDisplayOptions(CLI::App& command, ColorSettings& color) {
    command.add_option("--ocio-config", color.configFile,
                       "OpenColorIO config for display outputs (default: $OCIO, else built-in)");
    command.add_option("--display", color.display, "OCIO display (built-in: sRGB)");
    command.add_option("--view", color.view, "OCIO view (built-in: Standard, Filmic, Raw)");
}

void writeExrFile(const std::filesystem::path& file, const OIIO::ImageSpec& spec,
                  const std::vector<float>& pixels) {
    writeFileAtomically(file, [&](const std::filesystem::path& temp) {
        std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create("openexr");
        if (!out) return OIIO::geterror();
        if (!out->open(temp.string(), spec) ||
            !out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) || !out->close())
            return out->geterror();
        return std::string();
    });
}

bool isExr(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".exr";
}

}  // namespace strahl::app
