#pragma once
// A read-only view of contiguous elements (a pointer and a count), for the public headers' array parameters.
// Why not std::span: the installed headers must compile as C++17 (Android NDK and Unity native-plugin code is
// mostly C++17; docs/platforms.md), and <span> is C++20. ConstSpan converts implicitly from anything with
// std::data and std::size whose elements are T (std::vector, std::array, C arrays, and std::span in C++20 code),
// so call sites pass their containers as they did to std::span. It never owns: the viewed elements must outlive
// the call it is passed to.

#include <cstddef>
#include <iterator>
#include <type_traits>
#include <utility>

namespace gusuku {

namespace const_span_detail {
/// The element type a contiguous range holds (what std::data points to); a substitution failure for anything else.
template <typename Range>
using ElementOf = std::remove_cv_t<std::remove_pointer_t<decltype(std::data(std::declval<const Range&>()))>>;
}  // namespace const_span_detail

template <typename T>
class ConstSpan {
public:
    using element_type = const T;
    using value_type = std::remove_cv_t<T>;

    /// An empty view (`{}` at a call site).
    constexpr ConstSpan() noexcept = default;
    /// count elements from data; data may be null only when count is 0.
    constexpr ConstSpan(const T* data, size_t count) noexcept : data_(data), size_(count) {}
    /// Any contiguous range of T: std::vector<T>, std::array<T, N>, T[N], std::span<T>. Its elements must be T
    /// themselves: a range of a type derived from T would convert pointer-wise and be indexed with T's stride.
    template <typename Range,
              typename = std::enable_if_t<std::is_same_v<const_span_detail::ElementOf<Range>, value_type>>>
    constexpr ConstSpan(const Range& range) noexcept : data_(std::data(range)), size_(std::size(range)) {}

    constexpr const T* data() const noexcept { return data_; }
    constexpr size_t size() const noexcept { return size_; }
    constexpr bool empty() const noexcept { return size_ == 0; }
    /// index < size(); not checked (as std::span's).
    constexpr const T& operator[](size_t index) const noexcept { return data_[index]; }
    constexpr const T* begin() const noexcept { return data_; }
    constexpr const T* end() const noexcept { return data_ + size_; }

private:
    const T* data_ = nullptr;
    size_t size_ = 0;
};

}  // namespace gusuku
