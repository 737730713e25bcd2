#include "strahl/film/checkpoint.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <system_error>

#include "strahl/core/error.h"

namespace strahl {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'S', 'T', 'R', 'A', 'H', 'L', 'C', 'K'};
// 2: exact fixed-point sums (film/exact_sum.h) instead of float sums.
// 3: the adaptive sampling flags (Film::trackConvergence) after the other buffers.
constexpr uint32_t kVersion = 3;
// Fingerprints are a few hundred bytes; anything larger is not ours.
constexpr uint32_t kMaxFingerprint = 1u << 16;

}  // namespace

void writeCheckpoint(const Film& film, const fs::path& file, const std::string& fingerprint) {
    const fs::path temp = file.string() + ".partial";
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) fail(file.string(), ": cannot write the checkpoint (", temp.string(), ")");
        out.write(kMagic, sizeof kMagic);
        out.write(reinterpret_cast<const char*>(&kVersion), sizeof kVersion);
        const auto length = static_cast<uint32_t>(fingerprint.size());
        out.write(reinterpret_cast<const char*>(&length), sizeof length);
        out.write(fingerprint.data(), static_cast<std::streamsize>(fingerprint.size()));
        film.writeState(out);
        out.flush();
        if (!out) {
            std::error_code ec;
            fs::remove(temp, ec);
            fail(file.string(), ": cannot write the checkpoint (disk full?)");
        }
    }
    std::error_code ec;
    fs::rename(temp, file, ec);
    if (ec) {
        fs::remove(temp, ec);
        fail(file.string(), ": cannot write the checkpoint: ", ec.message());
    }
}

void readCheckpoint(Film& film, const fs::path& file, const std::string& fingerprint) {
    const std::string name = file.string();
    std::ifstream in(file, std::ios::binary);
    if (!in) fail(name, ": cannot read the checkpoint: no such file");
    char magic[sizeof kMagic] = {};
    in.read(magic, sizeof magic);
    if (!in || std::memcmp(magic, kMagic, sizeof kMagic) != 0)
        fail(name, ": not a strahl checkpoint");
    uint32_t version = 0, length = 0;
    in.read(reinterpret_cast<char*>(&version), sizeof version);
    if (!in || version != kVersion)
        fail(name, ": checkpoint format version ", version, ", this strahl reads version ",
             kVersion);
    in.read(reinterpret_cast<char*>(&length), sizeof length);
    if (!in || length > kMaxFingerprint) fail(name, ": checkpoint header is corrupt");
    std::string stored(length, '\0');
    in.read(stored.data(), length);
    if (!in) fail(name, ": checkpoint is truncated in its header");
    if (stored != fingerprint)
        fail(name, ": the checkpoint was made with other settings (checkpoint: ", stored,
             "; this render: ", fingerprint, ")");
    film.readState(in, name);
}

}  // namespace strahl
