#pragma once
// `strahl merge PART.exr... -o OUT.exr`: adds up the EXRs of a render split by
// sample ranges (`strahl render --spp N --sample-offset K` on several
// machines) into one image (docs/farm.md, "Sample splitting and merge").
//
// Parts that carry their exact sums (every EXR of a render with
// --sample-offset) must agree on size, data window, channels and
// strahl:split_fingerprint, and their sample ranges must be disjoint (an
// overlap would count samples twice); they need not be contiguous. Their sums
// are integers (film/exact_sum.h), so the result is bit for bit the image of
// one render of the union of their ranges, whatever the order of the parts,
// except the variance AOV (Chan's formula: the same statistics, rounded
// differently); and it carries the exact sums again, so merges merge.
// Other strahl EXRs (no exact sums) are combined as a mean weighted by their
// sample counts, with a one-line warning that the result is not bit-exact.

#include <string>
#include <vector>

#include "strahl/film/display_transform.h"

namespace CLI {
class App;
}

namespace strahl::app {

struct MergeOptions {
    std::vector<std::string> inputs;   // the parts, .exr
    std::vector<std::string> outputs;  // .exr (with AOVs) or display formats (beauty only)
    ColorSettings color;               // for display outputs
    bool quiet = false;
};

// Adds the `merge` subcommand and its options to `app`.
CLI::App* addMergeCommand(CLI::App& app, MergeOptions& options);

// Runs it; returns the exit status, throws strahl::Error for bad input.
int runMerge(const MergeOptions& options);

}  // namespace strahl::app
