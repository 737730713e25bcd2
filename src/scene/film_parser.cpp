// The scene file's "film" and "render" objects (film_parser.h).

#include "film_parser.h"

#include <algorithm>
#include <limits>
#include <string>

#include "strahl/core/error.h"
#include "strahl/core/filter.h"
#include "strahl/film/image_output.h"
#include "strahl/integrator/integrator.h"

namespace strahl::scene_detail {

namespace fs = std::filesystem;

namespace {

constexpr int64_t kMaxSpp = 65536;

}  // namespace

FilmDesc parseFilm(const JsonValue& v, const fs::path& folder) {
    v.requireKeys({"width", "height", "outputs", "aovs", "exr_float", "filter", "crop"});
    FilmDesc f;
    if (auto width = v.find("width")) f.width = static_cast<int>(width->integer(1, kMaxFilmSide));
    if (auto height = v.find("height"))
        f.height = static_cast<int>(height->integer(1, kMaxFilmSide));
    if (int64_t(f.width) * f.height > kMaxFilmPixels)
        v.fail("width x height = ", int64_t(f.width) * f.height, " pixels, more than the limit of ",
               kMaxFilmPixels, " (2^28)");

    if (auto outputs = v.find("outputs")) {
        for (size_t i = 0; i < outputs->size(); ++i) {
            const JsonValue output = outputs->at(i);
            fs::path path = resolvePath(folder, output);
            if (!hasExtension(path, supportedImageExtensions()))
                output.fail("'", path.filename().string(), "' is not a supported image format ",
                            "(extensions: ", joinList(supportedImageExtensions()), ")");
            f.outputs.push_back(std::move(path));
        }
    }
    if (auto aovs = v.find("aovs")) {
        for (size_t i = 0; i < aovs->size(); ++i) {
            const JsonValue aov = aovs->at(i);
            const std::string name = aov.oneOf(aovNames());
            const AovKind kind = *aovFromName(name);
            if (std::find(f.aovs.begin(), f.aovs.end(), kind) != f.aovs.end())
                aov.fail("'", name, "' is listed twice");
            f.aovs.push_back(kind);
        }
    }
    if (auto crop = v.find("crop")) {
        // [x0, y0, x1, y1]: pixels x0 <= x < x1, y0 <= y < y1, y = 0 at the top.
        if (!crop->raw().is_array() || crop->size() != 4)
            crop->fail("expected [x0, y0, x1, y1], four integers, got ", crop->describe());
        const int x0 = static_cast<int>(crop->at(0).integer(0, f.width - 1));
        const int y0 = static_cast<int>(crop->at(1).integer(0, f.height - 1));
        const int x1 = static_cast<int>(crop->at(2).integer(x0 + 1, f.width));
        const int y1 = static_cast<int>(crop->at(3).integer(y0 + 1, f.height));
        f.crop = PixelRect{x0, y0, x1, y1};
    }
    if (auto exrFloat = v.find("exr_float")) f.exrFloat = exrFloat->boolean();
    if (auto filter = v.find("filter")) {
        if (filter->raw().is_object()) {
            filter->requireKeys({"type", "radius"});
            f.filter = filter->get("type").oneOf(PixelFilter::names());
            if (auto radius = filter->find("radius")) {
                const float r = radius->number();
                // Beyond 16 pixels a filter is a blur, not an antialiasing filter.
                if (!(r > 0.0f && r <= 16.0f))
                    radius->fail("must be greater than 0 and at most 16 pixels, got ",
                                 radius->raw().dump());
                f.filterRadius = r;
            }
        } else {
            f.filter = filter->oneOf(PixelFilter::names());
        }
    }
    return f;
}

RenderDesc parseRender(const JsonValue& v) {
    v.requireKeys({"integrator", "spp", "seed", "max_depth", "russian_roulette",
                   "russian_roulette_depth", "russian_roulette_threshold", "ao_distance", "ao_samples", "clamp_direct",
                   "clamp_indirect", "filter_glossy", "light_selection", "hide_emitters", "denoise",
                   "adaptive"});
    RenderDesc r;
    if (auto integrator = v.find("integrator"))
        r.integrator = integrator->oneOf(integratorNames());
    if (auto spp = v.find("spp")) r.spp = static_cast<int>(spp->integer(1, kMaxSpp));
    if (auto seed = v.find("seed"))
        r.seed = seed->unsignedInteger(std::numeric_limits<uint64_t>::max());
    // Paths longer than 1024 bounces carry no measurable energy.
    if (auto depth = v.find("max_depth")) r.maxDepth = static_cast<int>(depth->integer(0, 1024));
    if (auto rr = v.find("russian_roulette")) r.russianRoulette = rr->boolean();
    if (auto hide = v.find("hide_emitters")) r.hideEmitters = hide->boolean();
    if (auto denoise = v.find("denoise")) r.denoise = denoise->boolean();
    if (auto selection = v.find("light_selection")) {
        const std::string name = selection->oneOf({"auto", "bvh", "power", "uniform"});
        r.lightSelection = name == "auto"      ? LightSelection::Auto
                           : name == "bvh"     ? LightSelection::Bvh
                           : name == "uniform" ? LightSelection::UniformEmitters
                                               : LightSelection::Power;
    }
    if (auto rr = v.find("russian_roulette_depth"))
        r.russianRouletteDepth = static_cast<int>(rr->integer(1, 1024));
    if (auto rr = v.find("russian_roulette_threshold")) {
        r.russianRouletteThreshold = rr->number();
        if (!(r.russianRouletteThreshold > 0.0f && r.russianRouletteThreshold <= 1.0f))
            rr->fail("must be in (0, 1], got ", r.russianRouletteThreshold);
    }
    if (auto distance = v.find("ao_distance")) {
        r.aoDistance = distance->number();
        if (!(r.aoDistance >= 0.0f)) distance->fail("must be non-negative, got ", r.aoDistance);
    }
    if (auto samples = v.find("ao_samples")) r.aoSamples = static_cast<int>(samples->integer(1, 4096));
    for (auto [key, value] : {std::pair{"clamp_direct", &r.clampDirect},
                              std::pair{"clamp_indirect", &r.clampIndirect},
                              std::pair{"filter_glossy", &r.filterGlossy}})
        if (auto given = v.find(key)) {
            *value = given->number();
            if (!(*value >= 0.0f)) given->fail("must be non-negative (0: off), got ", *value);
        }
    if (auto adaptive = v.find("adaptive")) {
        // {"threshold": t, "min_samples": n}: t > 0 turns it on (docs/adaptive.md).
        if (!adaptive->raw().is_object())
            adaptive->fail("expected {\"threshold\": T, \"min_samples\": N}, got ",
                           adaptive->describe());
        adaptive->requireKeys({"threshold", "min_samples"});
        // A relative error: at 1 a pixel's noise is as large as the pixel
        // (with nonnegative samples, no estimate exceeds it).
        r.adaptiveThreshold = adaptive->get("threshold").numberIn(0.0f, 1.0f);
        if (auto minSamples = adaptive->find("min_samples"))
            r.adaptiveMinSamples = static_cast<int>(minSamples->integer(2, kMaxSpp));
    }
    return r;
}

}  // namespace strahl::scene_detail
