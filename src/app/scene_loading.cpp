#include "scene_loading.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "strahl/core/process_memory.h"

namespace strahl::app {

// The command-line flags that change scene settings, as patches of the scene
// document (scene_document.h), then --set in the order given; a later patch
// wins. A flag for another scene key is one more line here. -o is not a patch:
// its files are relative to the current folder, not the scene's, and where an
// image is written is not part of what it is (applyOutputs).
std::vector<ScenePatch> scenePatches(const Options& o) {
    std::vector<ScenePatch> patches;
    const auto add = [&](const char* pointer, const nlohmann::json& value, std::string origin) {
        patches.push_back({pointer, value.dump(), std::move(origin)});
    };
    const auto flag = [](const char* name, const auto& value) {
        std::ostringstream text;
        text << name << " " << value;
        return text.str();
    };
    if (o.width) add("/film/width", *o.width, flag("--width", *o.width));
    if (o.height) add("/film/height", *o.height, flag("--height", *o.height));
    if (o.spp) add("/render/spp", *o.spp, flag("--spp", *o.spp));
    if (o.integrator) add("/render/integrator", *o.integrator, flag("--integrator", *o.integrator));
    if (o.maxDepth) add("/render/max_depth", *o.maxDepth, flag("--max-depth", *o.maxDepth));
    if (o.seed) add("/render/seed", *o.seed, flag("--seed", *o.seed));
    if (o.clampDirect)
        add("/render/clamp_direct", *o.clampDirect, flag("--clamp-direct", *o.clampDirect));
    if (o.clampIndirect)
        add("/render/clamp_indirect", *o.clampIndirect, flag("--clamp-indirect", *o.clampIndirect));
    if (o.filterGlossy)
        add("/render/filter_glossy", *o.filterGlossy, flag("--filter-glossy", *o.filterGlossy));
    if (o.adaptiveThreshold)
        add("/render/adaptive/threshold", *o.adaptiveThreshold,
            flag("--adaptive-threshold", *o.adaptiveThreshold));
    if (o.adaptiveMinSamples)
        add("/render/adaptive/min_samples", *o.adaptiveMinSamples,
            flag("--adaptive-min-samples", *o.adaptiveMinSamples));
    if (o.exrFloat) add("/film/exr_float", true, "--exr-float");
    if (o.denoiseRender) add("/render/denoise", true, "--denoise");
    if (!o.aovs.empty()) {
        std::vector<std::string> aovs;  // each once, in the order first given
        std::string origin;
        for (const std::string& a : o.aovs) {
            if (std::find(aovs.begin(), aovs.end(), a) == aovs.end()) aovs.push_back(a);
            origin += (origin.empty() ? "--aov " : " --aov ") + a;
        }
        add("/film/aovs", aovs, origin);
    }
    for (const std::string& argument : o.sets) patches.push_back(parseSetArgument(argument));
    return patches;
}

// The scene file as a document with the command line's patches applied.
SceneDocument patchedScene(const Options& o) {
    SceneDocument document = SceneDocument::read(o.scene, sceneDefines(o));
    for (const ScenePatch& patch : scenePatches(o)) document.apply(patch);
    return document;
}

BuildOptions buildOptions(const Options& o) {
    BuildOptions build;
    build.threads = o.threads.value_or(0);
    build.bvhQuality = bvhQualityFromName(o.bvhQuality);
    build.compact = o.compact;
    if (o.quads) build.quads = *o.quads ? QuadPolicy::Always : QuadPolicy::Never;
    if (o.memoryLimit) build.memoryLimitBytes = parseByteSize(*o.memoryLimit, "--memory-limit");
    return build;
}

}  // namespace strahl::app
