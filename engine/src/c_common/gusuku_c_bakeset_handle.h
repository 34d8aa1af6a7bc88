#pragma once
// What the C API (gusuku.h) keeps behind its opaque bake set handle: made by the runtime (gusuku_bakeset_create),
// gusuku_pack_loader (gusuku_bakeset_load_pack) and gusuku_loader (gusuku_bakeset_load), read by the runtime.
// Library gusuku_c_common, so that none of them includes another's private sources. Not installed.

#include "gusuku/formats/bakeset_data.h"
#include "gusuku/runtime/gusuku.h"

/// The bake set handle: a complete, checked BakeSetData in host memory.
struct gusuku_bakeset {
    gusuku::BakeSetData data;
};
