// The distributed module of a strahl built without MPI (STRAHL_MPI=OFF, the
// default): `--distributed` is refused with the way to get it, not ignored.

#include "strahl/core/error.h"
#include "strahl/distributed/distributed.h"

namespace strahl::distributed {

namespace {

[[noreturn]] void unavailable() {
    fail("--distributed: this strahl was built without MPI; configure with -DSTRAHL_MPI=ON "
         "(docs/distributed.md)");
}

}  // namespace

bool available() { return false; }

Role role() { return Role::Local; }

int run(const std::function<int()>&) { unavailable(); }

RenderStats renderImage(const World&, const Camera&, const Integrator&, Film&,
                        const RenderOptions&, const Settings&) {
    unavailable();
}

}  // namespace strahl::distributed
