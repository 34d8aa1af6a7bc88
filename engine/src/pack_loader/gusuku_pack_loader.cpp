// gusuku_bakeset_load_pack (gusuku_pack_loader.h): loadRuntimePack behind the C API's error convention.
#include <memory>

#include "gusuku/pack_loader/gusuku_pack_loader.h"
#include "gusuku/pack_loader/runtime_pack.h"
#include "gusuku_c_bakeset_handle.h"
#include "gusuku_c_errors.h"

extern "C" gusuku_result gusuku_bakeset_load_pack(const char* folder, gusuku_bakeset** out_bake_set) {
    using gusuku::c_api_detail::fail;
    if (out_bake_set == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_bakeset_load_pack: out_bake_set: is NULL");
    *out_bake_set = nullptr;
    if (folder == nullptr) return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_bakeset_load_pack: folder: is NULL");
    // "" would become "/manifest.json", a file at the root of the file system, not a folder the app named.
    if (folder[0] == '\0') return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_bakeset_load_pack: folder: is empty");
    try {
        auto bake_set = std::make_unique<gusuku_bakeset>();
        bake_set->data = gusuku::loadRuntimePack(folder);  // complete and checked, or it throws
        *out_bake_set = bake_set.release();
        return GUSUKU_OK;
    } catch (...) {
        return gusuku::c_api_detail::failFromCurrentException("gusuku_bakeset_load_pack");
    }
}
