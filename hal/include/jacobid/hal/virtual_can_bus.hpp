// SPDX-License-Identifier: MIT
#pragma once
// In-process virtual CAN bus: several endpoints, each a CanTransport with its own acceptance filters
// and fixed-size receive queue, so the decoders, the firmware cycle and the simulator can be tested
// together without a kernel. Single-threaded by design (the simulator and the tests step it from one
// thread); nothing allocates, every capacity is a template parameter.
//
// Delivery models:
//  - Immediate (default): send() delivers at once to every other matching endpoint, in send order.
//  - Stepped: send() only queues in the sender's transmit queue (TxCapacity; full -> TxQueueFull, as a
//    saturated bus would), and step(n) puts up to n frames on the bus, picking at each slot the pending
//    head frame that wins CAN arbitration (lowest identifier; a standard frame beats an extended one
//    with the same base id; a data frame beats a remote one). Frames of one sender stay in FIFO order.
// A receiver whose queue is full loses the frame and counts an overflow, like SO_RXQ_OVFL.
#include <array>
#include <cstddef>
#include <cstdint>

#include "jacobid/hal/can_frame.hpp"
#include "jacobid/hal/can_transport.hpp"
#include "jacobid/hal/fixed_queue.hpp"
#include "jacobid/span.hpp"

namespace jacobid::hal {

struct VirtualEndpointConfig {
    bool fd_frames = false;     // receive and send CAN FD frames (as CAN_RAW_FD_FRAMES)
    bool error_frames = true;   // count injected error frames (as CAN_RAW_ERR_FILTER = CAN_ERR_MASK)
    bool receive_own = false;   // also receive own frames (as CAN_RAW_RECV_OWN_MSGS)
};

// Priority of a frame in CAN arbitration: lower wins. Bits, most significant first: the 11-bit base
// id, IDE (standard 0 wins), the 18-bit id extension, RTR (data 0 wins).
constexpr std::uint64_t arbitration_key(const CanFrame& f) noexcept {
    const std::uint64_t base = f.extended() ? (f.id >> 18) & 0x7FFu : f.id & 0x7FFu;
    const std::uint64_t ide = f.extended() ? 1u : 0u;
    const std::uint64_t ext = f.extended() ? f.id & 0x3FFFFu : 0u;
    const std::uint64_t rtr = f.remote() ? 1u : 0u;
    return (base << 20) | (ide << 19) | (ext << 1) | rtr;
}

template <std::size_t MaxEndpoints, std::size_t RxCapacity, std::size_t TxCapacity = RxCapacity,
          std::size_t MaxFilters = 16>
class VirtualCanBus {
    static_assert(MaxEndpoints > 0, "a bus needs at least one endpoint slot");

public:
    enum class Delivery { Immediate, Stepped };

    class Endpoint final : public CanTransport {
    public:
        CanStatus send(const CanFrame& frame) noexcept override {
            if (!attached_) return CanStatus::NotOpen;
            if (!is_valid_frame(frame) || frame.error()) return CanStatus::InvalidFrame;
            if (frame.fd() && !config_.fd_frames) return CanStatus::FdNotEnabled;
            return bus_->transmit(*this, frame);
        }
        CanStatus receive(CanFrame& frame) noexcept override {
            if (!attached_) return CanStatus::NotOpen;
            if (!rx_.pop(frame)) return CanStatus::Empty;
            ++counters_.rx_frames;
            return CanStatus::Ok;
        }
        const CanCounters& counters() const noexcept override { return counters_; }
        bool is_open() const noexcept override { return attached_; }
        std::size_t rx_pending() const noexcept { return rx_.size(); }
        std::size_t tx_pending() const noexcept { return tx_.size(); }

    private:
        friend class VirtualCanBus;
        bool accepts(const CanFrame& f) const noexcept {
            if (f.fd() && !config_.fd_frames) return false;  // the kernel hides FD frames from classic sockets
            return matches_any(filters_, filter_count_, f);
        }

        VirtualCanBus* bus_ = nullptr;
        bool attached_ = false;
        VirtualEndpointConfig config_{};
        std::array<CanFilter, MaxFilters> filters_{};
        std::size_t filter_count_ = 0;
        FixedQueue<CanFrame, RxCapacity> rx_{};
        FixedQueue<CanFrame, TxCapacity> tx_{};
        CanCounters counters_{};
    };

    VirtualCanBus() noexcept {
        for (auto& e : endpoints_) e.bus_ = this;
    }
    // Endpoints point back at the bus: it cannot move.
    VirtualCanBus(const VirtualCanBus&) = delete;
    VirtualCanBus& operator=(const VirtualCanBus&) = delete;

    // Takes a free endpoint slot. On failure returns nullptr and sets *status (BusFull, TooManyFilters).
    Endpoint* attach(const VirtualEndpointConfig& config = {}, Span<const CanFilter> filters = {},
                     CanStatus* status = nullptr) noexcept {
        auto fail = [status](CanStatus s) -> Endpoint* {
            if (status) *status = s;
            return nullptr;
        };
        if (filters.size() > MaxFilters) return fail(CanStatus::TooManyFilters);
        for (auto& e : endpoints_) {
            if (e.attached_) continue;
            e.attached_ = true;
            e.config_ = config;
            e.filter_count_ = filters.size();
            for (std::size_t i = 0; i < filters.size(); ++i) e.filters_[i] = filters[i];
            e.rx_.clear();
            e.tx_.clear();
            e.counters_ = CanCounters{};
            if (status) *status = CanStatus::Ok;
            return &e;
        }
        return fail(CanStatus::BusFull);
    }

    // Frees the slot; the endpoint returns NotOpen until it is handed out again.
    void detach(Endpoint* e) noexcept {
        if (e != nullptr && e->bus_ == this) e->attached_ = false;
    }

    void set_delivery(Delivery d) noexcept { delivery_ = d; }
    Delivery delivery() const noexcept { return delivery_; }

    // Bus clock stamped on delivered frames (the simulator advances it; 0 by default).
    void set_time_ns(std::int64_t t) noexcept { now_ns_ = t; }
    std::int64_t time_ns() const noexcept { return now_ns_; }

    // Stepped mode: puts up to max_frames queued frames on the bus in arbitration order. Returns how many.
    std::size_t step(std::size_t max_frames) noexcept {
        std::size_t sent = 0;
        while (sent < max_frames) {
            Endpoint* winner = nullptr;
            for (auto& e : endpoints_) {
                if (!e.attached_ || e.tx_.empty()) continue;
                if (winner == nullptr || arbitration_key(e.tx_.front()) < arbitration_key(winner->tx_.front())) winner = &e;
            }
            if (winner == nullptr) break;
            CanFrame f;
            winner->tx_.pop(f);
            deliver(*winner, f);
            ++sent;
        }
        return sent;
    }

    // Frames waiting in transmit queues (Stepped mode).
    std::size_t pending() const noexcept {
        std::size_t n = 0;
        for (const auto& e : endpoints_) n += e.attached_ ? e.tx_.size() : 0;
        return n;
    }

    // An error frame as a controller would report it (class bits of linux/can/error.h, e.g. 0x40 bus-off).
    void inject_error_frame(std::uint32_t error_class) noexcept {
        for (auto& e : endpoints_) {
            if (!e.attached_ || !e.config_.error_frames) continue;
            ++e.counters_.error_frames;
            e.counters_.last_error_class = error_class;
        }
    }

private:
    CanStatus transmit(Endpoint& sender, const CanFrame& frame) noexcept {
        if (delivery_ == Delivery::Stepped) {
            if (!sender.tx_.push(frame)) {
                ++sender.counters_.tx_queue_full;
                return CanStatus::TxQueueFull;
            }
        } else {
            deliver(sender, frame);
        }
        ++sender.counters_.tx_frames;
        return CanStatus::Ok;
    }

    void deliver(const Endpoint& sender, CanFrame frame) noexcept {
        frame.timestamp_ns = now_ns_;
        for (auto& e : endpoints_) {
            if (!e.attached_) continue;
            if (&e == &sender && !e.config_.receive_own) continue;
            if (!e.accepts(frame)) continue;
            if (!e.rx_.push(frame)) ++e.counters_.rx_overflows;
        }
    }

    // No "{}" here on purpose: every Endpoint member has its own initializer, and with the extra
    // value-initialization GCC 12.2 at -O3 dropped the queue resets of attach() (dead-store elimination
    // under strict aliasing; clang and valgrind find nothing wrong). Caught by
    // HalVirtualBus.SteppedModeArbitratesByIdAndKeepsPerSenderFifo.
    std::array<Endpoint, MaxEndpoints> endpoints_;
    Delivery delivery_ = Delivery::Immediate;
    std::int64_t now_ns_ = 0;
};

}  // namespace jacobid::hal
