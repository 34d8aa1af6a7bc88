/* gusuku_loader.h: reads a bake set's files (docs/bakeset.md) into the C API's bake set handle (gusuku.h), for
 * apps that have the bake set as files. C99; include it from C or C++.
 *
 * Library gusuku_loader (CMake gusuku::loader, find_package(gusuku COMPONENTS loader)): gusuku_bakeset_load reads
 * the bake set's EXRs and glbs and links the tools' I/O stack (glTF, OpenEXR through OpenImageIO, JSON). It also
 * links gusuku_pack_loader, whose gusuku_bakeset_load_pack (gusuku/pack_loader/gusuku_pack_loader.h, the runtime
 * pack with the C++ standard library alone: what a phone app links) this header includes, so a desktop app has
 * both. An app that fills gusuku_bakeset_desc itself links gusuku::runtime alone. Errors follow gusuku.h: a
 * gusuku_result, and the message in gusuku_last_error_message(). */
#ifndef GUSUKU_GUSUKU_LOADER_H
#define GUSUKU_GUSUKU_LOADER_H

#include "gusuku/pack_loader/gusuku_pack_loader.h"
#include "gusuku/runtime/gusuku.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Loads folder/manifest.json and every file it names (gusuku/assets/bakeset_loader.h's loadBakeSet), checked as
 * gusuku_bakeset_create checks a desc, into a new bake set for gusuku_runtime_open(_headless); free it with
 * gusuku_bakeset_free. folder NULL or "": GUSUKU_ERROR_INVALID_ARGUMENT ("gusuku_bakeset_load: folder: is
 * empty"). A missing folder or file, a corrupt or inconsistent file: GUSUKU_ERROR_INVALID_BAKE_SET
 * with "gusuku_bakeset_load: FILE: FIELD: PROBLEM". Reads and decodes every file: O(bake set size) time and host
 * memory (tens of milliseconds for the sample's). */
gusuku_result gusuku_bakeset_load(const char* folder, gusuku_bakeset** out_bake_set);

#ifdef __cplusplus
}
#endif

#endif /* GUSUKU_GUSUKU_LOADER_H */
