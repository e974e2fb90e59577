// SPDX-License-Identifier: MIT
// In-process virtual bus: fan-out to several endpoints, filters, ordering, overflow of a full receive
// queue, tx-queue-full and arbitration in stepped mode, FD handling, error frames.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "hal_test_util.hpp"
#include "jacobid/hal/virtual_can_bus.hpp"

namespace {

using namespace jacobid::hal;
using jacobid::hal::test::frame;
using Bus = VirtualCanBus<4, 8, 3>;

std::vector<std::uint32_t> drain_ids(CanTransport& t) {
    std::vector<std::uint32_t> ids;
    CanFrame f;
    while (t.receive(f) == CanStatus::Ok) ids.push_back(f.id);
    return ids;
}

TEST(HalVirtualBus, DeliversToEveryOtherEndpointButNotTheSender) {
    Bus bus;
    auto* a = bus.attach();
    auto* b = bus.attach();
    auto* c = bus.attach();
    ASSERT_TRUE(a && b && c);
    ASSERT_EQ(a->send(frame(0x101, {0xDE, 0xAD})), CanStatus::Ok);
    CanFrame f;
    ASSERT_EQ(b->receive(f), CanStatus::Ok);
    EXPECT_EQ(f.id, 0x101u);
    EXPECT_EQ(f.len, 2);
    EXPECT_EQ(f.data[0], 0xDE);
    EXPECT_EQ(f.data[1], 0xAD);
    EXPECT_EQ(c->receive(f), CanStatus::Ok);
    EXPECT_EQ(a->receive(f), CanStatus::Empty);
    EXPECT_EQ(a->counters().tx_frames, 1u);
    EXPECT_EQ(b->counters().rx_frames, 1u);
}

TEST(HalVirtualBus, ReceiveOwnWhenConfigured) {
    Bus bus;
    VirtualEndpointConfig own;
    own.receive_own = true;
    auto* a = bus.attach(own);
    ASSERT_EQ(a->send(frame(0x5, {})), CanStatus::Ok);
    EXPECT_EQ(drain_ids(*a), std::vector<std::uint32_t>{0x5});
}

TEST(HalVirtualBus, FiltersSelectFramesPerEndpoint) {
    Bus bus;
    auto* tx = bus.attach();
    const CanFilter only_0x18x[] = {CanFilter{0x180, 0x780, CanIdFormat::Standard, false}};  // 0x180..0x1FF
    auto* rx = bus.attach({}, only_0x18x);
    auto* all = bus.attach();
    for (std::uint32_t id : {0x080u, 0x185u, 0x200u, 0x1FFu}) ASSERT_EQ(tx->send(frame(id, {1})), CanStatus::Ok);
    EXPECT_EQ(drain_ids(*rx), (std::vector<std::uint32_t>{0x185, 0x1FF}));
    EXPECT_EQ(drain_ids(*all), (std::vector<std::uint32_t>{0x080, 0x185, 0x200, 0x1FF}));
}

TEST(HalVirtualBus, KeepsSendOrderAndStampsTheBusTime) {
    Bus bus;
    auto* a = bus.attach();
    auto* b = bus.attach();
    bus.set_time_ns(1000);
    a->send(frame(0x300, {}));
    bus.set_time_ns(2000);
    a->send(frame(0x001, {}));  // lower id sent later: immediate mode keeps send order
    CanFrame f;
    ASSERT_EQ(b->receive(f), CanStatus::Ok);
    EXPECT_EQ(f.id, 0x300u);
    EXPECT_EQ(f.timestamp_ns, 1000);
    ASSERT_EQ(b->receive(f), CanStatus::Ok);
    EXPECT_EQ(f.id, 0x001u);
    EXPECT_EQ(f.timestamp_ns, 2000);
}

TEST(HalVirtualBus, FullReceiveQueueDropsAndCountsOverflow) {
    Bus bus;  // receive capacity 8
    auto* a = bus.attach();
    auto* b = bus.attach();
    for (std::uint32_t i = 0; i < 11; ++i) ASSERT_EQ(a->send(frame(i, {})), CanStatus::Ok);
    EXPECT_EQ(b->rx_pending(), 8u);
    EXPECT_EQ(b->counters().rx_overflows, 3u);
    // The oldest 8 are kept (the kernel also drops the newest when the socket buffer is full).
    const auto ids = drain_ids(*b);
    ASSERT_EQ(ids.size(), 8u);
    EXPECT_EQ(ids.front(), 0u);
    EXPECT_EQ(ids.back(), 7u);
}

TEST(HalVirtualBus, SteppedModeReportsTxQueueFullInsteadOfBlocking) {
    Bus bus;  // transmit capacity 3
    bus.set_delivery(Bus::Delivery::Stepped);
    auto* a = bus.attach();
    auto* b = bus.attach();
    for (int i = 0; i < 3; ++i) ASSERT_EQ(a->send(frame(0x10, {})), CanStatus::Ok);
    EXPECT_EQ(a->send(frame(0x10, {})), CanStatus::TxQueueFull);
    EXPECT_EQ(a->counters().tx_queue_full, 1u);
    EXPECT_EQ(a->counters().tx_frames, 3u);
    EXPECT_EQ(b->rx_pending(), 0u);  // nothing on the bus before step()
    EXPECT_EQ(bus.step(2), 2u);
    EXPECT_EQ(b->rx_pending(), 2u);
    EXPECT_EQ(a->send(frame(0x10, {})), CanStatus::Ok);  // room again
    EXPECT_EQ(bus.pending(), 2u);
}

TEST(HalVirtualBus, SteppedModeArbitratesByIdAndKeepsPerSenderFifo) {
    Bus bus;
    bus.set_delivery(Bus::Delivery::Stepped);
    auto* a = bus.attach();
    auto* b = bus.attach();
    auto* rx = bus.attach();
    a->send(frame(0x300, {}));
    a->send(frame(0x050, {}));                 // behind 0x300 in a's queue: waits for it
    b->send(frame(0x100, {}));
    b->send(frame(0x100, {}, kCanExtended));   // extended id 0x100: its 11-bit base id is 0x000
    EXPECT_EQ(bus.step(10), 4u);
    CanFrame f;
    std::vector<std::pair<std::uint32_t, bool>> got;
    while (rx->receive(f) == CanStatus::Ok) got.emplace_back(f.id, f.extended());
    // Heads: a 0x300, b 0x100 -> 0x100 (std). Heads: a 0x300, b ext 0x100 (base id 0x000) -> ext.
    // Then a's 0x300, then a's 0x050.
    const std::vector<std::pair<std::uint32_t, bool>> want = {{0x100, false}, {0x100, true}, {0x300, false}, {0x050, false}};
    EXPECT_EQ(got, want);
}

TEST(HalVirtualBus, ArbitrationKeyFollowsTheCanRules) {
    // Lower id wins; standard beats extended with the same 11-bit base; data beats remote.
    EXPECT_LT(arbitration_key(frame(0x100, {})), arbitration_key(frame(0x101, {})));
    EXPECT_LT(arbitration_key(frame(0x100, {})), arbitration_key(frame(0x100u << 18, {}, kCanExtended)));
    EXPECT_LT(arbitration_key(frame(0x100, {}, kCanRemote)), arbitration_key(frame(0x100u << 18, {}, kCanExtended)));
    EXPECT_LT(arbitration_key(frame(0x100, {})), arbitration_key(frame(0x100, {}, kCanRemote)));
    EXPECT_LT(arbitration_key(frame((0x100u << 18) | 5, {}, kCanExtended)), arbitration_key(frame(0x101, {})));
}

TEST(HalVirtualBus, FdFramesNeedFdEndpoints) {
    Bus bus;
    VirtualEndpointConfig fd;
    fd.fd_frames = true;
    auto* classic = bus.attach();
    auto* fd_tx = bus.attach(fd);
    auto* fd_rx = bus.attach(fd);
    CanFrame big = frame(0x42, {}, kCanFd | kCanBitRateSwitch);
    big.len = 64;
    big.data[63] = 0x5A;
    EXPECT_EQ(classic->send(big), CanStatus::FdNotEnabled);
    ASSERT_EQ(fd_tx->send(big), CanStatus::Ok);
    CanFrame f;
    EXPECT_EQ(classic->receive(f), CanStatus::Empty);
    ASSERT_EQ(fd_rx->receive(f), CanStatus::Ok);
    EXPECT_EQ(f.len, 64);
    EXPECT_EQ(f.data[63], 0x5A);
    EXPECT_TRUE(f.fd());
}

TEST(HalVirtualBus, RejectsInvalidFramesAndRunsOutOfSlots) {
    Bus bus;
    auto* a = bus.attach();
    EXPECT_EQ(a->send(frame(0x800, {})), CanStatus::InvalidFrame);
    EXPECT_EQ(a->send(frame(0x1, {}, kCanError)), CanStatus::InvalidFrame);
    bus.attach();
    bus.attach();
    bus.attach();
    CanStatus s = CanStatus::Ok;
    EXPECT_EQ(bus.attach({}, {}, &s), nullptr);
    EXPECT_EQ(s, CanStatus::BusFull);
    std::array<CanFilter, 17> too_many{};
    bus.detach(a);
    EXPECT_EQ(a->send(frame(0x1, {})), CanStatus::NotOpen);
    EXPECT_EQ(bus.attach({}, too_many, &s), nullptr);
    EXPECT_EQ(s, CanStatus::TooManyFilters);
    EXPECT_EQ(bus.attach({}, {}, &s), a);  // the freed slot is handed out again, fresh
    EXPECT_EQ(s, CanStatus::Ok);
    EXPECT_EQ(a->counters().tx_frames, 0u);
}

TEST(HalVirtualBus, ErrorFramesAreCountedNotDelivered) {
    Bus bus;
    VirtualEndpointConfig quiet;
    quiet.error_frames = false;
    auto* a = bus.attach();
    auto* b = bus.attach(quiet);
    bus.inject_error_frame(0x40);  // CAN_ERR_BUSOFF
    CanFrame f;
    EXPECT_EQ(a->receive(f), CanStatus::Empty);
    EXPECT_EQ(a->counters().error_frames, 1u);
    EXPECT_EQ(a->counters().last_error_class, 0x40u);
    EXPECT_EQ(b->counters().error_frames, 0u);
}

TEST(HalVirtualBus, DrainStopsAtTheSpanSizeAndLeavesTheRest) {
    Bus bus;
    auto* a = bus.attach();
    auto* b = bus.attach();
    for (std::uint32_t i = 0; i < 5; ++i) a->send(frame(i, {}));
    std::array<CanFrame, 3> out{};
    DrainResult r = b->drain(out);
    EXPECT_EQ(r.count, 3u);
    EXPECT_EQ(r.status, CanStatus::Ok);
    EXPECT_EQ(out[2].id, 2u);
    r = b->drain(out);
    EXPECT_EQ(r.count, 2u);
    EXPECT_EQ(out[0].id, 3u);
    r = b->drain(out);
    EXPECT_EQ(r.count, 0u);
}

}  // namespace
