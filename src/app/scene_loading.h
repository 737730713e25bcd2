#pragma once
// What render and info share between the command line and the library: the
// scene document with the command line's patches applied, and the build
// settings.

#include <vector>

#include "options.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_document.h"

namespace strahl::app {

// The command-line flags that change scene settings, as scene patches, then
// every --set in the order given (docs/cli.md#scene-patches).
std::vector<ScenePatch> scenePatches(const Options& o);

// The scene file as a document with scenePatches() applied.
SceneDocument patchedScene(const Options& o);

// The scene build settings of the command line (threads, BVH quality and
// mode, memory limit).
BuildOptions buildOptions(const Options& o);

}  // namespace strahl::app
