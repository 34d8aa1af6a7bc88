// gusuku_bakeset_load (gusuku_loader.h): gusuku_assets' loadBakeSet behind the C API's error convention.
#include "gusuku/loader/gusuku_loader.h"

#include <memory>

#include "gusuku/assets/bakeset_loader.h"
#include "gusuku_c_bakeset_handle.h"
#include "gusuku_c_errors.h"

extern "C" gusuku_result gusuku_bakeset_load(const char* folder, gusuku_bakeset** out_bake_set) {
    using gusuku::c_api_detail::fail;
    if (out_bake_set == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_bakeset_load: out_bake_set: is NULL");
    *out_bake_set = nullptr;
    if (folder == nullptr) return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_bakeset_load: folder: is NULL");
    // "" would become "/manifest.json", a file at the root of the file system, not a folder the app named.
    if (folder[0] == '\0') return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_bakeset_load: folder: is empty");
    try {
        auto bake_set = std::make_unique<gusuku_bakeset>();
        bake_set->data = gusuku::loadBakeSet(folder);  // complete and checked, or it throws
        *out_bake_set = bake_set.release();
        return GUSUKU_OK;
    } catch (...) {
        return gusuku::c_api_detail::failFromCurrentException("gusuku_bakeset_load");
    }
}
