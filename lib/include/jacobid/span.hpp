// SPDX-License-Identifier: MIT
#pragma once
// A minimal non-owning view of contiguous memory (C++17 has no std::span). The core passes buffers the
// caller owns through it, so that nothing in lib/ allocates.
#include <cstddef>
#include <utility>

namespace jacobid {

template <typename T>
class Span {
public:
    constexpr Span() noexcept = default;
    constexpr Span(T* data, std::size_t size) noexcept : data_(data), size_(size) {}
    template <std::size_t N>
    constexpr Span(T (&array)[N]) noexcept : data_(array), size_(N) {}
    // Any contiguous container with data()/size() (std::array, std::vector on the host side).
    template <typename Container, typename = decltype(std::declval<Container&>().data())>
    constexpr Span(Container& c) noexcept : data_(c.data()), size_(c.size()) {}
    // Span<T> converts to Span<const T>.
    template <typename U>
    constexpr Span(const Span<U>& other) noexcept : data_(other.data()), size_(other.size()) {}

    constexpr T* data() const noexcept { return data_; }
    constexpr std::size_t size() const noexcept { return size_; }
    constexpr bool empty() const noexcept { return size_ == 0; }
    constexpr T& operator[](std::size_t i) const noexcept { return data_[i]; }
    constexpr T* begin() const noexcept { return data_; }
    constexpr T* end() const noexcept { return data_ + size_; }
    constexpr Span subspan(std::size_t offset, std::size_t count) const noexcept { return {data_ + offset, count}; }

private:
    T* data_ = nullptr;
    std::size_t size_ = 0;
};

}  // namespace jacobid
