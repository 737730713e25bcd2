// render.hide_emitters (Mitsuba's hide_emitters; docs/scene-format.md): camera
// rays see no emission, neither an emitting surface nor the sky, while what
// the emitters light is unchanged; for the path and direct integrators alike.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "render_helpers.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

// Looking down at a grey floor (left half of the image) next to an emitting
// quad (right half) under a blue sky.
SceneDesc scene(const std::string& integrator, bool hide) {
    return parseSceneText(R"({
      "camera": { "type": "orthographic", "eye": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0],
                  "window": [-2, 2, -1, 1] },
      "film": { "width": 8, "height": 4 },
      "background": [0.1, 0.2, 0.9],
      "render": { "integrator": ")" + integrator + R"(", "spp": 16, "max_depth": 2, "hide_emitters": )" +
                              (hide ? "true" : "false") + R"( },
      "materials": [ { "name": "grey", "color": 0.5 }, { "name": "lamp", "type": "emissive", "emission": 3 } ],
      "shapes": [
        { "type": "mesh", "material": "grey", "positions": [[-2,-1,0],[0,-1,0],[0,1,0],[-2,1,0]], "indices": [0,1,2, 0,2,3] },
        { "type": "mesh", "material": "lamp", "positions": [[0,-1,0.01],[1,-1,0.01],[1,1,0.01],[0,1,0.01]], "indices": [0,1,2, 0,2,3] } ]
    })", test::scratchDir("hide-emitters") / "scene.json");
}

TEST(HideEmitters, CameraRaysSeeNoEmissionButTheLitSurfacesAreUnchanged) {
    for (const char* integrator : {"path", "direct"}) {
        SCOPED_TRACE(integrator);
        const std::vector<float> shown = test::renderFilm(scene(integrator, false)).resolveBeauty();
        const std::vector<float> hidden = test::renderFilm(scene(integrator, true)).resolveBeauty();
        const auto pixel = [](const std::vector<float>& image, int x, int y) {
            return &image[size_t(3 * (y * 8 + x))];
        };
        // The floor (x 0..3): lit by the sky and the lamp the same way.
        for (int c = 0; c < 3; ++c) EXPECT_EQ(pixel(hidden, 1, 1)[c], pixel(shown, 1, 1)[c]);
        EXPECT_GT(pixel(shown, 1, 1)[0], 0.0f);
        // The lamp (x 4, 5) and the sky (x 6, 7): black when hidden.
        EXPECT_NEAR(pixel(shown, 4, 1)[0], 3.0f, 1e-5f);
        for (int x : {4, 7})
            for (int c = 0; c < 3; ++c) EXPECT_EQ(pixel(hidden, x, 2)[c], 0.0f) << x;
        EXPECT_GT(pixel(shown, 7, 2)[2], 0.5f);
    }
}

}  // namespace
}  // namespace strahl
