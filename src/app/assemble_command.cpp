// `strahl assemble`: region EXRs -> one full EXR. The checks come first, on
// the headers alone (every file is opened before any pixel is read, so a bad
// set fails fast): compatible regions, no overlap, full coverage. Then each
// region is read straight into its place in one buffer of the full image
// (float: half values survive the round trip exactly) and the buffer is
// written through the temp-then-rename writer with the first region's
// header, its data window widened to the display window.

#include "assemble_command.h"

#include <CLI/CLI.hpp>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <system_error>
#include <vector>

#include "image_files.h"
#include "strahl/core/error.h"
#include "strahl/core/pixel_rect.h"
#include "strahl/film/image_output.h"

namespace strahl::app {

namespace {

namespace fs = std::filesystem;

struct Region {
    std::string file;
    OIIO::ImageSpec spec;
    PixelRect rect;  // the data window, in display-window coordinates
};

bool same(const PixelRect& a, const PixelRect& b) {
    return a.x0 == b.x0 && a.y0 == b.y0 && a.x1 == b.x1 && a.y1 == b.y1;
}

std::string describe(const PixelRect& r) { return concat(r.x0, " ", r.y0, " ", r.x1, " ", r.y1); }

Region readHeader(const std::string& file) {
    std::error_code ec;
    if (!fs::exists(file, ec)) fail(file, ": no such file");
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(file);
    if (!in) fail(file, ": cannot read: ", OIIO::geterror());
    if (std::string(in->format_name()) != "openexr")
        fail(file, ": not an EXR file (assemble stitches the EXRs of strahl render --region)");
    Region r{file, in->spec(), {}};
    if (r.spec.deep) fail(file, ": deep EXR images cannot be assembled");
    r.rect = {r.spec.x, r.spec.y, r.spec.x + r.spec.width, r.spec.y + r.spec.height};
    return r;
}

PixelRect displayWindow(const OIIO::ImageSpec& spec) {
    return {spec.full_x, spec.full_y, spec.full_x + spec.full_width,
            spec.full_y + spec.full_height};
}

std::string join(const std::vector<std::string>& names) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ",") + n;
    return list;
}

// Every channel's type, also for files whose channels share one type.
std::vector<std::string> channelTypes(const OIIO::ImageSpec& spec) {
    std::vector<std::string> types;
    for (int c = 0; c < spec.nchannels; ++c) types.push_back(spec.channelformat(c).c_str());
    return types;
}

// The regions must be pieces of one image: the first region is the
// reference, and the message names it and the one that differs.
void checkCompatible(const Region& a, const Region& b) {
    const PixelRect da = displayWindow(a.spec), db = displayWindow(b.spec);
    if (!same(da, db))
        fail(a.file, " and ", b.file, ": different display windows (", describe(da), " and ",
             describe(db), "): not regions of one image");
    if (a.spec.channelnames != b.spec.channelnames)
        fail(a.file, " and ", b.file, ": different channels (", join(a.spec.channelnames),
             " and ", join(b.spec.channelnames), ")");
    if (channelTypes(a.spec) != channelTypes(b.spec))
        fail(a.file, " and ", b.file, ": different channel types (", join(channelTypes(a.spec)),
             " and ", join(channelTypes(b.spec)), ")");
    for (const char* key : {"strahl:fingerprint", "strahl:frame"}) {
        const std::string va = a.spec.get_string_attribute(key);
        const std::string vb = b.spec.get_string_attribute(key);
        if (va != vb)
            fail(a.file, " and ", b.file, ": different ", key, " ('", va, "' and '", vb,
                 "'): not rendered with the same settings");
    }
}

PixelRect intersection(const PixelRect& a, const PixelRect& b) {
    return {std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1),
            std::min(a.y1, b.y1)};
}

// The pixels of `full` no region covers, as rectangles: the rows are cut into
// bands at every region edge; in each band the uncovered runs of x are the
// complement of the regions spanning it, and a run continuing the same run
// of the band above extends that rectangle.
std::vector<PixelRect> uncovered(const PixelRect& full, const std::vector<Region>& regions) {
    std::vector<int> ys{full.y0, full.y1};
    for (const Region& r : regions) ys.insert(ys.end(), {r.rect.y0, r.rect.y1});
    std::sort(ys.begin(), ys.end());
    ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
    std::vector<PixelRect> gaps;
    for (size_t i = 0; i + 1 < ys.size(); ++i) {
        const int y0 = ys[i], y1 = ys[i + 1];
        std::vector<std::pair<int, int>> spans;
        for (const Region& r : regions)
            if (r.rect.y0 <= y0 && r.rect.y1 >= y1) spans.emplace_back(r.rect.x0, r.rect.x1);
        std::sort(spans.begin(), spans.end());
        int x = full.x0;
        const auto addGap = [&](int x0, int x1) {
            for (PixelRect& g : gaps)
                if (g.x0 == x0 && g.x1 == x1 && g.y1 == y0) {
                    g.y1 = y1;
                    return;
                }
            gaps.push_back({x0, y0, x1, y1});
        };
        for (const auto& [s0, s1] : spans) {
            if (s0 > x) addGap(x, s0);
            x = std::max(x, s1);
        }
        if (x < full.x1) addGap(x, full.x1);
    }
    return gaps;
}

std::string describeGaps(const std::vector<PixelRect>& gaps) {
    constexpr size_t kListed = 8;
    std::string list;
    for (size_t i = 0; i < std::min(gaps.size(), kListed); ++i)
        list += (i ? ", " : "") + describe(gaps[i]);
    if (gaps.size() > kListed) list += concat(" and ", gaps.size() - kListed, " more");
    return list;
}

}  // namespace

CLI::App* addAssembleCommand(CLI::App& app, AssembleOptions& o) {
    CLI::App* assemble = app.add_subcommand(
        "assemble",
        "Stitch the EXRs of strahl render --region runs into the full image (docs/farm.md)");
    assemble->add_option("regions", o.inputs, "Region EXRs, each from strahl render --region")
        ->required();
    assemble->add_option("-o,--output", o.output, "The full image (.exr)")->required();
    assemble->add_flag("--allow-gaps", o.allowGaps,
                       "Fill pixels no region covers with 0 and mark the image partial, instead "
                       "of failing");
    assemble->add_flag("--allow-partial", o.allowPartial,
                       "Accept regions marked partial (interrupted renders) and mark the image "
                       "partial, instead of failing");
    assemble->add_flag("-q,--quiet", o.quiet, "No summary line and no warnings");
    return assemble;
}

int runAssemble(const AssembleOptions& o) {
    const fs::path output = o.output;
    checkOutputPath(output);  // a bad name or folder fails before anything is read
    if (output.extension() != ".exr" && output.extension() != ".EXR")
        fail(o.output, ": assemble writes EXR only (convert it afterwards for display)");

    std::vector<Region> regions;
    for (const std::string& file : o.inputs) regions.push_back(readHeader(file));
    const Region& first = regions.front();
    const PixelRect full = displayWindow(first.spec);
    bool partial = false;
    std::string stopped;
    for (const Region& r : regions) {
        checkCompatible(first, r);
        if (!full.contains(r.rect))
            fail(r.file, ": its pixels ", describe(r.rect), " reach outside the display window ",
                 describe(full));
        if (r.spec.get_string_attribute("strahl:partial") == "1") {
            const std::string why = r.spec.get_string_attribute("strahl:stopped");
            const std::string what =
                concat(r.file, ": is partial (strahl:partial = 1", why.empty() ? "" : ", stopped by ",
                       why, ", ", r.spec.get_string_attribute("strahl:samples"), " of ",
                       r.spec.get_int_attribute("strahl:spp"), " samples per pixel)");
            if (!o.allowPartial)
                fail(what, ": render it again, or pass --allow-partial to assemble a partial image");
            if (!o.quiet) std::fprintf(stderr, "strahl: warning: %s\n", what.c_str());
            partial = true;
            if (stopped.empty()) stopped = "partial region " + r.file;
        }
    }
    for (size_t i = 0; i < regions.size(); ++i)
        for (size_t k = i + 1; k < regions.size(); ++k) {
            const PixelRect overlap = intersection(regions[i].rect, regions[k].rect);
            if (!overlap.empty())
                fail(regions[i].file, " and ", regions[k].file, " overlap in pixels ",
                     describe(overlap), " (X0 Y0 X1 Y1): each pixel must come from one region");
        }
    // Without overlaps, the regions cover the image exactly when their areas add up to it.
    int64_t covered = 0;
    for (const Region& r : regions) covered += r.rect.area();
    if (covered < full.area()) {
        const std::string what =
            concat("the regions leave ", full.area() - covered, " of ", full.area(),
                   " pixels uncovered: ", describeGaps(uncovered(full, regions)));
        if (!o.allowGaps)
            fail(what, " (render them with --region, or pass --allow-gaps to fill them with 0)");
        if (!o.quiet) std::fprintf(stderr, "strahl: warning: %s; filled with 0\n", what.c_str());
        partial = true;
        stopped = "gaps";
    }

    // The pixels: each region read into its place in the full image.
    const size_t channels = static_cast<size_t>(first.spec.nchannels);
    const size_t pixelBytes = channels * sizeof(float);
    std::vector<float> pixels(static_cast<size_t>(full.area()) * channels, 0.0f);
    float renderSeconds = 0.0f;
    int samples = std::numeric_limits<int>::max();
    for (const Region& r : regions) {
        std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(r.file);
        if (!in) fail(r.file, ": cannot read: ", OIIO::geterror());
        float* origin = pixels.data() + (static_cast<size_t>(r.rect.y0 - full.y0) *
                                             static_cast<size_t>(full.width()) +
                                         static_cast<size_t>(r.rect.x0 - full.x0)) *
                                            channels;
        if (!in->read_image(0, 0, 0, first.spec.nchannels, OIIO::TypeDesc::FLOAT, origin,
                            static_cast<OIIO::stride_t>(pixelBytes),
                            static_cast<OIIO::stride_t>(pixelBytes * size_t(full.width()))))
            fail(r.file, ": cannot read its pixels: ", in->geterror());
        renderSeconds += r.spec.get_float_attribute("strahl:renderTime");
        const std::string s = r.spec.get_string_attribute("strahl:samples");
        if (!s.empty()) samples = std::min(samples, std::atoi(s.c_str()));
    }

    OIIO::ImageSpec spec = first.spec;
    spec.x = full.x0;
    spec.y = full.y0;
    spec.width = full.width();
    spec.height = full.height();
    spec.tile_width = spec.tile_height = spec.tile_depth = 0;  // written as scanlines
    spec.attribute("strahl:partial", partial ? "1" : "0");
    spec.attribute("strahl:regions", static_cast<int>(regions.size()));
    if (partial)
        spec.attribute("strahl:stopped", stopped);
    else
        spec.erase_attribute("strahl:stopped");
    if (samples != std::numeric_limits<int>::max())
        spec.attribute("strahl:samples", std::to_string(samples));
    // The render time of the whole image: the regions' times added up.
    if (first.spec.find_attribute("strahl:renderTime"))
        spec.attribute("strahl:renderTime", renderSeconds);
    writeExrFile(output, spec, pixels);
    if (!o.quiet)
        std::fprintf(stderr, "assembled %zu regions into %s (%dx%d%s)\n", regions.size(),
                     o.output.c_str(), full.width(), full.height(), partial ? ", partial" : "");
    return 0;
}

}  // namespace strahl::app
