#include "strahl/film/display_transform.h"

#include <OpenColorIO/OpenColorIO.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <system_error>
#include <tuple>
#include <utility>
#include <vector>

#include "builtin_config.h"
#include "strahl/core/error.h"

namespace OCIO = OCIO_NAMESPACE;

namespace strahl {
namespace {

// A loaded config and how to name it: `label` in description(), `origin` in
// error messages, `identity` as the processor cache key.
struct ConfigSource {
    OCIO::ConstConfigRcPtr config;
    std::string label;
    std::string origin;
    std::string identity;
};

// `origin` says where the file name came from, for the messages: the file
// itself for --ocio-config, "$OCIO (file)" for the environment.
ConfigSource loadConfigFile(const std::string& file, const std::string& origin) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
        fail(origin, ": OpenColorIO config not found (no such file)");
    OCIO::ConstConfigRcPtr config;
    try {
        config = OCIO::Config::CreateFromFile(file.c_str());
        config->validate();
    } catch (const OCIO::Exception& e) {
        fail(origin, ": invalid OpenColorIO config: ", e.what());
    }
    if (!config->hasRole(OCIO::ROLE_SCENE_LINEAR))
        fail(origin, ": the OpenColorIO config has no '", OCIO::ROLE_SCENE_LINEAR,
             "' role; strahl needs it to know which colour space its linear Rec.709 output is");
    // The cache ID hashes the config's content and context, so an edited file
    // is a new identity; the file name keeps equal copies' descriptions apart.
    return {config, file, origin, file + "\n" + config->getCacheID()};
}

ConfigSource loadConfig(const ColorSettings& settings) {
    if (!settings.configFile.empty())
        return loadConfigFile(settings.configFile, settings.configFile);
    const char* env = std::getenv("OCIO");
    if (env != nullptr && *env != '\0') return loadConfigFile(env, concat("$OCIO (", env, ")"));
    return {detail::builtinColorConfig(), "builtin", "strahl's built-in OpenColorIO config",
            "builtin"};
}

std::string displayList(const OCIO::Config& config) {
    std::string list;
    for (int i = 0; i < config.getNumDisplays(); ++i)
        list += concat(i > 0 ? ", " : "", "'", config.getDisplay(i), "'");
    return list.empty() ? "none" : list;
}

std::string viewList(const OCIO::Config& config, const std::string& display) {
    std::string list;
    for (int i = 0; i < config.getNumViews(display.c_str()); ++i)
        list += concat(i > 0 ? ", " : "", "'", config.getView(display.c_str(), i), "'");
    return list.empty() ? "none" : list;
}

bool hasDisplay(const OCIO::Config& config, const std::string& display) {
    for (int i = 0; i < config.getNumDisplays(); ++i)
        if (display == config.getDisplay(i)) return true;
    return false;
}

bool hasView(const OCIO::Config& config, const std::string& display, const std::string& view) {
    for (int i = 0; i < config.getNumViews(display.c_str()); ++i)
        if (view == config.getView(display.c_str(), i)) return true;
    return false;
}

// Empty names select the config's defaults; unknown names are errors that list
// what the config offers.
std::pair<std::string, std::string> resolveDisplayView(const ConfigSource& source,
                                                       const ColorSettings& settings) {
    const OCIO::Config& config = *source.config;
    const std::string display =
        settings.display.empty() ? config.getDefaultDisplay() : settings.display;
    if (display.empty()) fail(source.origin, ": the OpenColorIO config defines no display");
    if (!hasDisplay(config, display))
        fail(source.origin, ": unknown display '", display, "' (available: ", displayList(config),
             ")");
    const std::string view =
        settings.view.empty() ? config.getDefaultView(display.c_str()) : settings.view;
    if (view.empty()) fail(source.origin, ": display '", display, "' has no views");
    if (!hasView(config, display, view))
        fail(source.origin, ": unknown view '", view, "' for display '", display,
             "' (available: ", viewList(config, display), ")");
    return {display, view};
}

class OcioDisplayTransform final : public DisplayTransform {
  public:
    OcioDisplayTransform(OCIO::ConstCPUProcessorRcPtr processor, std::string description)
        : processor_(std::move(processor)), description_(std::move(description)) {}

    void apply(std::vector<float>& rgb, int width, int height) const override {
        if (width < 0 || height < 0 ||
            rgb.size() != 3 * static_cast<size_t>(width) * static_cast<size_t>(height))
            fail("display transform: ", rgb.size(), " values do not make a ", width, "x", height,
                 " RGB image");
        if (rgb.empty()) return;
        OCIO::PackedImageDesc image(rgb.data(), width, height, 3);
        processor_->apply(image);  // CPU processors are immutable and thread-safe
    }

    std::string description() const override { return description_; }

  private:
    OCIO::ConstCPUProcessorRcPtr processor_;
    std::string description_;
};

std::shared_ptr<const DisplayTransform> build(const ConfigSource& source,
                                              const std::string& display, const std::string& view) {
    try {
        OCIO::ConstProcessorRcPtr processor = source.config->getProcessor(
            OCIO::ROLE_SCENE_LINEAR, display.c_str(), view.c_str(), OCIO::TRANSFORM_DIR_FORWARD);
        OCIO::ConstCPUProcessorRcPtr cpu = processor->getOptimizedCPUProcessor(
            OCIO::BIT_DEPTH_F32, OCIO::BIT_DEPTH_F32, OCIO::OPTIMIZATION_DEFAULT);
        return std::make_shared<OcioDisplayTransform>(
            std::move(cpu), concat(source.label, " / ", display, " / ", view));
    } catch (const OCIO::Exception& e) {
        fail(source.origin, ": display '", display, "' view '", view, "': ", e.what());
    }
}

}  // namespace

std::shared_ptr<const DisplayTransform> DisplayTransform::get(const ColorSettings& settings) {
    const ConfigSource source = loadConfig(settings);
    const auto [display, view] = resolveDisplayView(source, settings);

    using Key = std::tuple<std::string, std::string, std::string>;
    static std::mutex mutex;
    static std::map<Key, std::shared_ptr<const DisplayTransform>> cache;

    const std::lock_guard<std::mutex> lock(mutex);
    Key key{source.identity, display, view};
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(std::move(key), build(source, display, view)).first;
    return it->second;
}

}  // namespace strahl
