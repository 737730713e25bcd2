#pragma once
// Scene-linear to display conversion through OpenColorIO.
//
// Config choice, first match wins: an explicit file (--ocio-config), $OCIO, and
// otherwise strahl's built-in config (OCIO 2.1 has no ocio:// built-ins): the
// reference space is linear Rec.709; display "sRGB" has views "Standard"
// (piecewise sRGB EOTF inverse), "Filmic" (a soft-shoulder tone curve before the
// sRGB encoding) and "Raw". Processors are cached per (config, display, view).

#include <memory>
#include <string>
#include <vector>

namespace strahl {

struct ColorSettings {
    std::string configFile;  // empty: $OCIO, else the built-in config
    std::string display;     // empty: the config's default display
    std::string view;        // empty: the display's default view
};

class DisplayTransform {
public:
    // Throws strahl::Error naming the config, display or view that is wrong.
    static std::shared_ptr<const DisplayTransform> get(const ColorSettings& settings);

    // In place, interleaved RGB, scene-linear in, display-encoded [0,1] out.
    virtual void apply(std::vector<float>& rgb, int width, int height) const = 0;
    virtual std::string description() const = 0;  // "config / display / view"
    virtual ~DisplayTransform() = default;
};

}  // namespace strahl
