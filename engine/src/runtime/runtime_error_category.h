#pragma once
// The runtime's one error family (runtime.h, "Errors") at its catch sites: whatever a call's work throws reaches the
// app as a RuntimeError whose code still says what went wrong. A catch-all that made every exception kDevice told an
// app to blame the GPU for host memory or a bad input it could have fixed. Private to gusuku_runtime.

#include <exception>
#include <new>
#include <stdexcept>
#include <string>

#include "gusuku/formats/input_error.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku::runtime_detail {

/// Rethrows the exception being handled (call only inside a catch block) as a RuntimeError of its own category:
///   - a RuntimeError as it is;
///   - std::bad_alloc as kOutOfMemory, "gusuku runtime: out of host memory " + `doing`;
///   - a bad input (InputError, std::invalid_argument) as `input_code`, the code of what this call was given
///     (kInvalidBakeSet while opening, kInvalidFrame for a frame);
///   - anything else as kDevice: checkVk's std::runtime_error for a failed Vulkan call, or an unknown exception.
[[noreturn]] inline void rethrowAsRuntimeError(RuntimeErrorCode input_code, const char* doing) {
    try {
        throw;
    } catch (const RuntimeError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw RuntimeError(RuntimeErrorCode::kOutOfMemory, std::string("gusuku runtime: out of host memory ") + doing);
    } catch (const InputError& error) {
        throw RuntimeError(input_code, std::string("gusuku runtime: ") + error.what());
    } catch (const std::invalid_argument& error) {
        throw RuntimeError(input_code, std::string("gusuku runtime: ") + error.what());
    } catch (const std::exception& error) {
        throw RuntimeError(RuntimeErrorCode::kDevice, std::string("gusuku runtime: ") + error.what());
    } catch (...) {
        throw RuntimeError(RuntimeErrorCode::kDevice, std::string("gusuku runtime: an unknown exception ") + doing);
    }
}

}  // namespace gusuku::runtime_detail
