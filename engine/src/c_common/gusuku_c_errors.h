#pragma once
// The C API's error reporting (gusuku.h, "Errors"), shared by every library with C entry points: the runtime,
// gusuku_pack_loader, gusuku_loader and gusuku_weather. One thread-local last message per process, defined once in
// library gusuku_c_common, so gusuku_last_error_message returns what any of them set. Not installed.

#include "gusuku/runtime/gusuku.h"

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

}  // namespace gusuku::c_api_detail
