#include "strahl/job/fingerprints.h"

#include <cstdint>
#include <sstream>

namespace strahl {

namespace {

std::string hex(uint64_t value) {
    std::ostringstream text;
    text << std::hex << value;
    return text.str();
}

}  // namespace

std::string imageFingerprint(const SceneDocument& document) {
    return "scene " + document.file().filename().string() + " fnv1a " +
           hex(document.hash({"/film/outputs"}));
}

std::string checkpointFingerprint(const std::string& imageFingerprint, const PixelRect& crop,
                                  int tileSize, std::optional<int> sampleOffset) {
    std::ostringstream f;
    f << imageFingerprint << ", crop " << crop.x0 << "," << crop.y0 << "," << crop.x1 << ","
      << crop.y1 << ", tile " << tileSize;
    if (sampleOffset) f << ", samples from " << *sampleOffset;
    return f.str();
}

std::string splitFingerprint(AccelKind accel, const SceneDocument& document) {
    return "scene " + document.file().filename().string() + " without spp fnv1a " +
           hex(document.hash({"/film/outputs", "/render/spp"})) + ", accel " + accelName(accel);
}

}  // namespace strahl
