// SPDX-License-Identifier: MIT
#pragma once
// FIFO of fixed capacity over a std::array: push fails (returns false) instead of growing, which is how
// the HAL models a full hardware/kernel queue without touching the heap.
#include <array>
#include <cstddef>

namespace jacobid::hal {

template <typename T, std::size_t Capacity>
class FixedQueue {
    static_assert(Capacity > 0, "a queue needs room for at least one element");

public:
    bool push(const T& value) noexcept {
        if (size_ == Capacity) return false;
        items_[(head_ + size_) % Capacity] = value;
        ++size_;
        return true;
    }
    bool pop(T& out) noexcept {
        if (size_ == 0) return false;
        out = items_[head_];
        head_ = (head_ + 1) % Capacity;
        --size_;
        return true;
    }
    // Oldest element; only valid when !empty().
    const T& front() const noexcept { return items_[head_]; }
    void clear() noexcept { head_ = size_ = 0; }
    std::size_t size() const noexcept { return size_; }
    bool empty() const noexcept { return size_ == 0; }
    bool full() const noexcept { return size_ == Capacity; }
    static constexpr std::size_t capacity() noexcept { return Capacity; }

private:
    std::array<T, Capacity> items_{};
    std::size_t head_ = 0;
    std::size_t size_ = 0;
};

}  // namespace jacobid::hal
