#pragma once
// What the C API (gusuku.h) keeps behind its opaque bake set handle, and its error reporting, shared by the
// runtime's gusuku_c_api.cpp and gusuku_loader's gusuku_bakeset_load (which makes the same handle from files).
// Not a public header: not installed.

#include <exception>
#include <string>

#include "gusuku/maths/bakeset_data.h"
#include "gusuku/runtime/gusuku.h"

/// The bake set handle: a complete, checked BakeSetData in host memory.
struct gusuku_bakeset {
    gusuku::BakeSetData data;
};

namespace gusuku::c_api_detail {

/// A fixed buffer for a one-line message: writing one never allocates, so never throws.
struct MessageBuffer {
    char text[GUSUKU_MESSAGE_CAPACITY] = {};
    /// Copies message (cut to fit), newlines turned into spaces so it stays one line.
    void set(const char* message) noexcept;
};

/// Records a failure in the calling thread's message (and in `handle_message` when given) and returns `code`.
gusuku_result fail(gusuku_result code, const char* message, MessageBuffer* handle_message = nullptr) noexcept;

/// Maps the exception being handled (call inside a catch block) to a code and records its message, prefixed
/// with `context` ("gusuku_runtime_open: ..."): RuntimeError by its code, InputError as an invalid bake set,
/// std::bad_alloc as out of memory, any other exception as internal.
gusuku_result failFromCurrentException(const char* context, MessageBuffer* handle_message = nullptr) noexcept;

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
