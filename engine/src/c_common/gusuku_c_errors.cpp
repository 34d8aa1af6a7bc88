// The C API's error reporting (gusuku.h, "Errors"): the codes' names, the calling thread's last message, and
// exceptions turned into codes. Library gusuku_c_common, which every library with C entry points links, so the
// message and gusuku_last_error_message are defined once; code which needs only this (the C helpers' fuzz target,
// tests/fuzz/fuzz_c_helpers.cpp) compiles without the rest of the runtime.
#include <cstdio>
#include <exception>
#include <new>

#include "gusuku/formats/input_error.h"
#include "gusuku/runtime/gusuku.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku_c_errors.h"

namespace gusuku::c_api_detail {

namespace {

thread_local MessageBuffer t_thread_message;

gusuku_result codeOf(RuntimeErrorCode code) {
    switch (code) {
    case RuntimeErrorCode::kInvalidBakeSet: return GUSUKU_ERROR_INVALID_BAKE_SET;
    case RuntimeErrorCode::kInvalidFrame: return GUSUKU_ERROR_INVALID_FRAME;
    case RuntimeErrorCode::kDevice: return GUSUKU_ERROR_DEVICE;
    case RuntimeErrorCode::kOutOfMemory: return GUSUKU_ERROR_OUT_OF_MEMORY;
    }
    return GUSUKU_ERROR_INTERNAL;
}

/// "context: message" into a local buffer, then recorded; no allocation.
gusuku_result failWithContext(gusuku_result code, const char* context, const char* message,
                              MessageBuffer* handle_message) noexcept {
    char text[GUSUKU_MESSAGE_CAPACITY];
    std::snprintf(text, sizeof text, "%s: %s", context, message);
    return fail(code, text, handle_message);
}

}  // namespace

void MessageBuffer::set(const char* message) noexcept {
    size_t length = 0;
    for (; message != nullptr && message[length] != '\0' && length + 1 < sizeof text; ++length)
        text[length] = (message[length] == '\n' || message[length] == '\r') ? ' ' : message[length];
    text[length] = '\0';
}

gusuku_result fail(gusuku_result code, const char* message, MessageBuffer* handle_message) noexcept {
    t_thread_message.set(message);
    if (handle_message != nullptr) handle_message->set(message);
    return code;
}

gusuku_result failFromCurrentException(const char* context, MessageBuffer* handle_message) noexcept {
    try {
        throw;
    } catch (const RuntimeError& error) {
        return failWithContext(codeOf(error.code()), context, error.what(), handle_message);
    } catch (const InputError& error) {
        return failWithContext(GUSUKU_ERROR_INVALID_BAKE_SET, context, error.what(), handle_message);
    } catch (const std::bad_alloc&) {
        return failWithContext(GUSUKU_ERROR_OUT_OF_MEMORY, context, "out of host memory", handle_message);
    } catch (const std::exception& error) {
        return failWithContext(GUSUKU_ERROR_INTERNAL, context, error.what(), handle_message);
    } catch (...) {
        return failWithContext(GUSUKU_ERROR_INTERNAL, context, "an unknown exception", handle_message);
    }
}

}  // namespace gusuku::c_api_detail

extern "C" {

const char* gusuku_result_name(gusuku_result result) {
    switch (result) {
    case GUSUKU_OK: return "GUSUKU_OK";
    case GUSUKU_ERROR_INVALID_BAKE_SET: return "GUSUKU_ERROR_INVALID_BAKE_SET";
    case GUSUKU_ERROR_INVALID_FRAME: return "GUSUKU_ERROR_INVALID_FRAME";
    case GUSUKU_ERROR_DEVICE: return "GUSUKU_ERROR_DEVICE";
    case GUSUKU_ERROR_OUT_OF_MEMORY: return "GUSUKU_ERROR_OUT_OF_MEMORY";
    case GUSUKU_ERROR_INVALID_ARGUMENT: return "GUSUKU_ERROR_INVALID_ARGUMENT";
    case GUSUKU_ERROR_INTERNAL: return "GUSUKU_ERROR_INTERNAL";
    }
    return "GUSUKU_UNKNOWN_RESULT";
}

const char* gusuku_last_error_message(void) { return gusuku::c_api_detail::t_thread_message.text; }

}  // extern "C"
