#include "cli_render.h"

#include <OpenImageIO/imageio.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "strahl/core/error.h"

namespace fs = std::filesystem;

namespace strahl::bench {

std::string quoted(const std::string& text) {
    std::string out = "'";
    for (char c : text) {
        if (c == '\'')
            out += "'\\''";
        else
            out.push_back(c);
    }
    return out + "'";
}

Channels readChannels(const fs::path& file) {
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) fail(file.string(), ": cannot read: ", OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    const size_t n = size_t(spec.width) * size_t(spec.height), c = size_t(spec.nchannels);
    std::vector<float> pixels(n * c);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()))
        fail(file.string(), ": cannot read: ", in->geterror());
    Channels out;
    for (size_t k = 0; k < c; ++k) {
        std::vector<float>& plane = out[spec.channel_name(int(k))];
        plane.resize(n);
        for (size_t i = 0; i < n; ++i) plane[i] = pixels[i * c + k];
    }
    return out;
}

std::vector<float> rgb(const Channels& channels, const std::string& prefix) {
    const auto& r = channels.at(prefix + "R");
    const auto& g = channels.at(prefix + "G");
    const auto& b = channels.at(prefix + "B");
    std::vector<float> out;
    out.reserve(3 * r.size());
    for (size_t i = 0; i < r.size(); ++i) out.insert(out.end(), {r[i], g[i], b[i]});
    return out;
}

RenderTimes renderWithCli(const fs::path& scene, const fs::path& out,
                          const std::vector<std::string>& args) {
    const fs::path stats = out.string() + ".stats.json";
    std::string command = quoted(STRAHL_BINARY) + " render " + quoted(scene.string()) +
                          " -q --exr-float -o " + quoted(out.string()) + " --stats " +
                          quoted(stats.string());
    for (const std::string& a : args) {
        command += ' ';
        command += quoted(a);
    }
    if (std::system(command.c_str()) != 0) fail("render failed: ", command);
    std::ifstream in(stats);
    const nlohmann::json j = nlohmann::json::parse(in);
    fs::remove(stats);
    const nlohmann::json& t = j["timings"];
    return {t["render"].get<double>(),      t["denoise"].get<double>(), t["load"].get<double>(),
            t["bvh"].get<double>(),         t["first_pixel"].get<double>(), t["total"].get<double>()};
}

void writeOpenSphereScene(const std::filesystem::path& file) {
    std::ofstream out(file);
    out << R"({
  "camera": { "eye": [0, 1.6, 4.5], "look_at": [0, 0.9, 0], "up": [0, 1, 0], "fov": 40 },
  "film": { "width": 512, "height": 512 },
  "render": { "integrator": "path", "spp": 16, "max_depth": 8 },
  "materials": [ { "name": "grey", "color": 0.8 } ],
  "shapes": [
    { "type": "implicit", "surface": { "type": "sphere", "radius": 1 },
      "transform": [ { "translate": [0, 1, 0] } ], "material": "grey" },
    { "type": "mesh", "material": "grey",
      "positions": [[-10, 0, -10], [10, 0, -10], [10, 0, 10], [-10, 0, 10]],
      "indices": [0, 3, 2, 0, 2, 1] }
  ],
  "lights": [ { "type": "point", "position": [3, 5, 4], "intensity": 40 } ]
}
)";
    if (!out) fail(file.string(), ": cannot write");
}


}  // namespace strahl::bench
