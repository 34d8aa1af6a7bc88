#pragma once
// The runtime's private C API pieces: the bake set desc's conversion, beside the handle and the error reporting
// that it shares with the loaders and gusuku_weather (library gusuku_c_common, engine/src/c_common).
// Not a public header: not installed.

#include <exception>
#include <string>

#include "gusuku/formats/bakeset_data.h"
#include "gusuku/runtime/gusuku.h"
#include "gusuku_c_bakeset_handle.h"
#include "gusuku_c_errors.h"

namespace gusuku::c_api_detail {

/// The first problem with a desc: its code and "FIELD: PROBLEM" (no message: none).
struct DescProblem {
    gusuku_result code = GUSUKU_OK;
    std::string message;
    explicit operator bool() const { return !message.empty(); }
};

/// The desc (this library's full layout: gusuku_bakeset_create reads the app's over zeros first) into `data`
/// (gusuku_c_api_bakeset.cpp): arrays, site, building, slots and ground albedo copied and checked; the
/// first problem found, or none. findBakeSetProblem then checks the whole as for any bake set.
DescProblem convertDesc(const gusuku_bakeset_desc& desc, gusuku::BakeSetData& data);

}  // namespace gusuku::c_api_detail
