#include "texture_parser.h"

#include <string>
#include <vector>

namespace strahl::scene_detail {

void requireTextureKeys(const JsonValue& v, std::initializer_list<std::string_view> own) {
    std::vector<std::string_view> keys(own);
    keys.insert(keys.end(), std::begin(kTextureSamplingKeys), std::end(kTextureSamplingKeys));
    v.requireKeys(keys);
}

void parseTextureSampling(const JsonValue& v, TextureRef& out) {
    if (auto wrap = v.find("wrap")) {
        const std::string w = wrap->oneOf({"repeat", "mirror", "clamp"});
        out.sampling.wrap = w == "repeat" ? TextureWrap::Repeat
                            : w == "mirror" ? TextureWrap::Mirror
                                            : TextureWrap::Clamp;
    }
    if (auto filter = v.find("filter")) {
        const std::string f = filter->oneOf({"footprint", "bilinear", "nearest"});
        out.sampling.filter = f == "footprint"  ? TextureFilter::Footprint
                              : f == "bilinear" ? TextureFilter::Bilinear
                                                : TextureFilter::Nearest;
    }
    // [[a, b, c], [d, e, f]]: (s, t) to (a s + b t + c, d s + e t + f).
    if (auto transform = v.find("uv_transform")) {
        if (!transform->raw().is_array() || transform->size() != 2)
            transform->fail("expected two rows [[a, b, c], [d, e, f]]");
        for (int row = 0; row < 2; ++row) {
            const JsonValue r = transform->at(static_cast<size_t>(row));
            if (!r.raw().is_array() || r.size() != 3) r.fail("expected a row of three numbers");
            for (int col = 0; col < 3; ++col)
                out.stTransform[col][row] = r.at(static_cast<size_t>(col)).number();
        }
    }
}

TextureRef parseImageTexture(const JsonValue& v, const std::filesystem::path& folder) {
    if (!v.raw().is_object()) v.fail("expected {\"texture\": file, ...}, got ", v.describe());
    requireTextureKeys(v, {"texture"});
    TextureRef texture;
    texture.file = resolveExistingFile(folder, v.get("texture"), "texture file");
    parseTextureSampling(v, texture);
    return texture;
}

}  // namespace strahl::scene_detail
