#include "merge_command.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "image_files.h"
#include "strahl/core/error.h"
#include "strahl/film/exact_part.h"
#include "strahl/film/exr_input.h"
#include "strahl/film/image_output.h"

namespace strahl::app {

namespace {

// The image channels (beauty and AOVs) with their types, without the exact
// state (strahl.*), which only some parts may carry.
std::vector<std::string> imageChannels(const ExrHeader& h) {
    std::vector<std::string> channels;
    for (size_t c = 0; c < h.channels.size(); ++c)
        if (h.channels[c].rfind("strahl.", 0) != 0)
            channels.push_back(h.channels[c] + " (" + h.channelTypes[c] + ")");
    return channels;
}

// "a, b" : the items of `of` that `in` lacks.
std::string missing(const std::vector<std::string>& of, const std::vector<std::string>& in) {
    std::string text;
    for (const std::string& item : of)
        if (std::find(in.begin(), in.end(), item) == in.end())
            text += (text.empty() ? "" : ", ") + item;
    return text;
}

// Every part must be a piece of the same image as the first.
void checkSameImage(const ExrHeader& first, const ExrHeader& part) {
    const std::string a = part.file.string(), b = first.file.string();
    if (part.fullWidth != first.fullWidth || part.fullHeight != first.fullHeight)
        fail(a, ": image size ", part.fullWidth, "x", part.fullHeight, " differs from ", b, " (",
             first.fullWidth, "x", first.fullHeight, ")");
    const PixelRect& w = part.dataWindow;
    const PixelRect& f = first.dataWindow;
    if (w.x0 != f.x0 || w.y0 != f.y0 || w.x1 != f.x1 || w.y1 != f.y1)
        fail(a, ": data window ", w.x0, ",", w.y0, ",", w.x1, ",", w.y1, " differs from ", b,
             " (", f.x0, ",", f.y0, ",", f.x1, ",", f.y1, "): parts must be the same crop");
    const std::vector<std::string> mine = imageChannels(part), theirs = imageChannels(first);
    if (mine != theirs) {
        const std::string extra = missing(mine, theirs), lacking = missing(theirs, mine);
        fail(a, ": its channels differ from ", b, "'s (other --aov or --exr-float):",
             extra.empty() ? "" : " it has " + extra, extra.empty() || lacking.empty() ? "" : ";",
             lacking.empty() ? "" : " it lacks " + lacking);
    }
}

// Exact parts: one render's settings, no sample counted twice.
void checkExactParts(const std::vector<const ExrHeader*>& parts) {
    const ExrHeader& first = *parts.front();
    for (const ExrHeader* part : parts)
        if (part->metadata.part->fingerprint != first.metadata.part->fingerprint)
            fail(part->file.string(), ": rendered with other settings than ", first.file.string(),
                 " (", part->metadata.part->fingerprint, "; ", first.metadata.part->fingerprint,
                 ")");
    struct Owned {
        SampleRange range;
        const ExrHeader* part;
    };
    std::vector<Owned> ranges;
    for (const ExrHeader* part : parts)
        for (const SampleRange& r : part->metadata.part->ranges) ranges.push_back({r, part});
    std::sort(ranges.begin(), ranges.end(),
              [](const Owned& x, const Owned& y) { return x.range.begin < y.range.begin; });
    for (size_t i = 1; i < ranges.size(); ++i) {
        const Owned& x = ranges[i - 1];
        const Owned& y = ranges[i];
        if (y.range.begin < x.range.end)
            fail(y.part->file.string(), ": its samples ", formatRanges({y.range}),
                 " overlap the samples ", formatRanges({x.range}), " of ", x.part->file.string(),
                 ": merging would count samples ", y.range.begin, "-",
                 std::min(x.range.end, y.range.end), " twice");
    }
}

}  // namespace

CLI::App* addMergeCommand(CLI::App& app, MergeOptions& o) {
    CLI::App* merge = app.add_subcommand(
        "merge",
        "Add up the EXRs of a render split by sample ranges (render --spp N --sample-offset K) "
        "into one image; bit-identical to a single render of all their samples");
    merge->add_option("parts", o.inputs,
                      "EXR outputs of strahl render --sample-offset (any order; their sample "
                      "ranges must not overlap). Other strahl EXRs are averaged by sample count, "
                      "not bit-exactly")
        ->required();
    merge->add_option("-o,--output", o.outputs,
                      "Output image; repeat for several. .exr: every channel of the parts, with "
                      "the exact sums (so merges can be merged); .png/.jpg/.tif: the beauty "
                      "through the OCIO display transform")
        ->required();
    addDisplayOptions(*merge, o.color);
    merge->add_flag("-q,--quiet", o.quiet, "No summary line and no warnings");
    return merge;
}

int runMerge(const MergeOptions& o) {
    // Bad outputs and OCIO configs fail before any part is read.
    bool displayOutput = false;
    for (const std::string& out : o.outputs) {
        checkOutputPath(out);
        displayOutput = displayOutput || !isExr(out);
    }
    if (displayOutput || !o.color.configFile.empty()) DisplayTransform::get(o.color);

    // Every header first: a mismatch fails before any pixels are read.
    std::vector<ExrHeader> parts;
    for (const std::string& input : o.inputs) parts.push_back(readExrHeader(input));
    for (const ExrHeader& part : parts) checkSameImage(parts.front(), part);
    std::vector<const ExrHeader*> exactParts;
    for (const ExrHeader& part : parts)
        if (part.exact()) exactParts.push_back(&part);
    if (!exactParts.empty()) checkExactParts(exactParts);
    const bool exact = exactParts.size() == parts.size();
    if (!exact && !o.quiet) {
        const auto plain = std::find_if(parts.begin(), parts.end(),
                                        [](const ExrHeader& p) { return !p.exact(); });
        std::fprintf(stderr,
                     "strahl: warning: %s: carries no exact sums (not rendered with "
                     "--sample-offset): the merged image is a sample-weighted mean, not "
                     "bit-exact\n",
                     plain->file.string().c_str());
    }
    // Exact parts in sample order: the sums do not care, but the objectid AOV
    // is the first sample's and the variance is combined pairwise in this
    // order, so the result does not depend on the order of the arguments.
    std::vector<size_t> order(parts.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    const auto firstSample = [&](size_t i) {
        return parts[i].exact() ? parts[i].metadata.part->ranges.front().begin : 0u;
    };
    if (exact)
        std::stable_sort(order.begin(), order.end(),
                         [&](size_t a, size_t b) { return firstSample(a) < firstSample(b); });
    const ExrHeader& earliest = parts[order.front()];

    Film film = readExrFilm(earliest);
    double renderSeconds = 0.0;
    uint64_t samples = 0;
    bool partial = false;
    std::vector<SampleRange> ranges;
    for (size_t i : order) {
        const ExrHeader& part = parts[i];
        if (i != order.front()) film.merge(readExrFilm(part), part.file.string());
        samples += part.samples;
        renderSeconds += part.metadata.renderSeconds;
        if (part.exact())
            ranges.insert(ranges.end(), part.metadata.part->ranges.begin(),
                          part.metadata.part->ranges.end());
        const auto flag = part.metadata.extra.find("partial");
        partial = partial || (flag != part.metadata.extra.end() && flag->second == "1");
    }

    // The earliest part's metadata, with the merged counts.
    ImageMetadata metadata = earliest.metadata;
    metadata.renderSeconds = renderSeconds;  // machine time, all parts together
    metadata.spp = static_cast<int>(samples);  // at most ExactSum::kMaxSamples (Film::merge)
    metadata.extra["samples"] = std::to_string(samples);
    metadata.extra["partial"] = partial ? "1" : "0";
    if (!partial) metadata.extra.erase("stopped");
    // strahl:fingerprint names the settings of one render, its spp included:
    // the merged image is no longer that render's.
    metadata.extra.erase("fingerprint");
    metadata.part.reset();
    if (exact) metadata.part = SamplePart{joinRanges(ranges), earliest.metadata.part->fingerprint};

    OutputSettings output;
    output.exrFloat = earliest.exrFloat;
    output.color = o.color;
    for (const std::string& out : o.outputs) {
        writeImage(film, out, output, metadata);
        if (!o.quiet) std::fprintf(stderr, "wrote %s\n", out.c_str());
    }
    if (!o.quiet)
        std::fprintf(stderr, "merged %zu part%s: %llu samples per pixel%s%s\n", parts.size(),
                     parts.size() == 1 ? "" : "s",
                     static_cast<unsigned long long>(samples),
                     exact ? ", sample indices " : " (weighted mean, not bit-exact)",
                     exact ? formatRanges(metadata.part->ranges).c_str() : "");
    return 0;
}

}  // namespace strahl::app
