/* gusuku_pack_loader.h: reads a bake set's runtime pack (docs/bakeset.md, "The runtime pack") into the C API's
 * bake set handle (gusuku.h). C99; include it from C or C++.
 *
 * Library gusuku_pack_loader (CMake gusuku::pack_loader): the C++ standard library only, what a phone app links
 * beside gusuku::runtime, built in the runtime-only configuration too; its C++ entry is
 * gusuku/pack_loader/runtime_pack.h's loadRuntimePack. Errors follow gusuku.h: a gusuku_result, and the message in
 * gusuku_last_error_message(). */
#ifndef GUSUKU_GUSUKU_PACK_LOADER_H
#define GUSUKU_GUSUKU_PACK_LOADER_H

#include "gusuku/runtime/gusuku.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Loads the runtime pack in folder (a pack folder, or a bake set folder holding pack/; docs/bakeset.md "The runtime
 * pack", gusuku/pack_loader/runtime_pack.h's loadRuntimePack), checked as gusuku_bakeset_create checks a desc, into a
 * new bake set; free it with gusuku_bakeset_free. folder NULL or "": GUSUKU_ERROR_INVALID_ARGUMENT. A missing
 * file, a truncated or malformed KTX2 or pack.bin, sizes that disagree with the manifest:
 * GUSUKU_ERROR_INVALID_BAKE_SET with "gusuku_bakeset_load_pack: FILE: FIELD: PROBLEM". */
gusuku_result gusuku_bakeset_load_pack(const char* folder, gusuku_bakeset** out_bake_set);

#ifdef __cplusplus
}
#endif

#endif /* GUSUKU_GUSUKU_PACK_LOADER_H */
