#include "strahl/film/denoise_layers.h"

namespace strahl {

std::string halfLayerName(int half) {
    return half == 0 ? "half0" : "half1";
}

std::vector<std::string> halfLayerChannels(int half) {
    const std::string layer = halfLayerName(half);
    std::vector<std::string> names;
    for (const char* c : {"R", "G", "B"}) names.push_back(layer + "." + c);
    for (const char* c : {"R", "G", "B"}) names.push_back(layer + ".albedo." + c);
    for (const char* c : {"X", "Y", "Z"}) names.push_back(layer + ".normal." + c);
    names.push_back(layer + ".depth.Z");
    return names;
}

bool isDenoiseLayerChannel(std::string_view channel) {
    return channel.starts_with("noisy.") || channel.starts_with("half0.") ||
           channel.starts_with("half1.");
}

void appendHalfLayers(const Film& film, std::vector<std::string>& names,
                      std::vector<std::vector<float>>& planes) {
    for (int half = 0; half < 2; ++half) {
        const std::vector<std::string> channels = halfLayerChannels(half);
        names.insert(names.end(), channels.begin(), channels.end());
        planes.push_back(film.resolveHalfBeauty(half));
        planes.push_back(film.resolveHalfAov(half, AovKind::Albedo));
        planes.push_back(film.resolveHalfAov(half, AovKind::Normal));
        planes.push_back(film.resolveHalfAov(half, AovKind::Depth));
    }
}

}  // namespace strahl
