// AresDriver over a fake Transport: decoding, draining, sequence gaps,
// checksum errors, stale frames, disconnects and stop().
#include <gtest/gtest.h>

#include <deque>
#include <vector>

#include "millsim/driver/AresDriver.h"
#include "millsim/driver/AresProtocol.h"

using namespace millsim;

namespace {

// Frames queue up as a device would deliver them; sent frames are kept for
// inspection. Shared state survives the driver taking ownership.
struct FakeWire {
  std::deque<std::vector<std::uint8_t>> incoming;
  std::vector<std::vector<std::uint8_t>> sent;
  bool connected = true;
  bool closed = false;
  int failSends = 0;  // the next n sends fail with Error
  std::vector<std::chrono::microseconds> receiveTimeouts;
};

class FakeTransport final : public Transport {
public:
  explicit FakeTransport(FakeWire& w) : w_(w) {}
  TransferResult send(std::span<const std::uint8_t> frame, std::chrono::microseconds) override {
    if (!w_.connected || w_.closed) return {TransferStatus::Disconnected, 0};
    if (w_.failSends > 0) {
      --w_.failSends;
      return {TransferStatus::Error, 0};
    }
    w_.sent.emplace_back(frame.begin(), frame.end());
    return {TransferStatus::Ok, 0};
  }
  TransferResult receiveNewest(std::span<std::uint8_t> buffer, std::chrono::microseconds timeout,
                               std::uint64_t& discarded) override {
    w_.receiveTimeouts.push_back(timeout);
    discarded = 0;
    if (!w_.connected || w_.closed) return {TransferStatus::Disconnected, 0};
    if (w_.incoming.empty()) return {TransferStatus::Timeout, 0};
    discarded = w_.incoming.size() - 1;
    const std::vector<std::uint8_t> f = w_.incoming.back();
    w_.incoming.clear();
    std::copy(f.begin(), f.end(), buffer.begin());
    return {TransferStatus::Ok, f.size()};
  }
  bool connected() const override { return w_.connected && !w_.closed; }
  std::string describe() const override { return "ARES device 1209:0001 (fake)"; }
  void close() override { w_.closed = true; }

private:
  FakeWire& w_;
};

std::vector<std::uint8_t> stateFrame(std::uint32_t seq, float x, std::uint16_t buttons = 0,
                                     std::uint16_t status = 0) {
  ares::StateFrame s;
  s.sequence = seq;
  s.position = {x, 0.02f, -0.01f};
  s.orientation = {0.f, 0.f, 1.f, 0.f};
  s.buttons = buttons;
  s.status = status;
  std::vector<std::uint8_t> b(ares::kStateFrameSize);
  ares::encode(s, b);
  return b;
}

ares::CommandFrame decodeCommand(const std::vector<std::uint8_t>& b) {
  ares::CommandFrame c;
  EXPECT_EQ(ares::decode(b, c), ares::DecodeError::None);
  return c;
}

struct Rig {
  FakeWire wire;
  AresDriver driver{std::make_unique<FakeTransport>(wire), AresDriverOptions{}};
};

}  // namespace

TEST(AresDriver, ReadsPoseAndButton) {
  Rig r;
  r.wire.incoming.push_back(stateFrame(1, 0.05f, ares::kButtonMain));
  const DeviceReading d = r.driver.read(0.0, 0.001);
  ASSERT_TRUE(d.valid);
  EXPECT_NEAR(d.pose.position.x, 0.05, 1e-7);
  EXPECT_NEAR(d.pose.position.y, 0.02, 1e-7);
  EXPECT_EQ(d.pose.orientation.y, 1.0);
  EXPECT_TRUE(d.button);
  EXPECT_EQ(r.driver.counters().framesReceived, 1u);
  EXPECT_LE(r.wire.receiveTimeouts.back(), std::chrono::microseconds(1000));
}

TEST(AresDriver, NeverWaitsLongerThanTheFrame) {
  Rig r;
  r.driver.read(0.0, 0.0002);  // a 5 kHz loop
  EXPECT_LE(r.wire.receiveTimeouts.back(), std::chrono::microseconds(200));
}

TEST(AresDriver, NothingFreshMeansInvalidHoldingTheLastPose) {
  Rig r;
  r.wire.incoming.push_back(stateFrame(1, 0.03f));
  ASSERT_TRUE(r.driver.read(0.0, 0.001).valid);
  const DeviceReading d = r.driver.read(0.001, 0.001);  // nothing arrived
  EXPECT_FALSE(d.valid);
  EXPECT_NEAR(d.pose.position.x, 0.03, 1e-7);
  EXPECT_FALSE(r.driver.failed());
  // The same frame again (a repeat) or an older one is not fresh either.
  r.wire.incoming.push_back(stateFrame(1, 0.03f));
  EXPECT_FALSE(r.driver.read(0.002, 0.001).valid);
  r.wire.incoming.push_back(stateFrame(0, 0.03f));
  EXPECT_FALSE(r.driver.read(0.003, 0.001).valid);
  r.wire.incoming.push_back(stateFrame(2, 0.04f));
  EXPECT_TRUE(r.driver.read(0.004, 0.001).valid);
}

TEST(AresDriver, TakesTheNewestFrameAndCountsOnlyRealGaps) {
  Rig r;
  r.wire.incoming.push_back(stateFrame(10, 0.01f));
  r.driver.read(0.0, 0.001);
  // Three frames waiting: the newest is used, the two older are drained, not gaps.
  for (std::uint32_t s : {11u, 12u, 13u}) r.wire.incoming.push_back(stateFrame(s, 0.001f * s));
  const DeviceReading d = r.driver.read(0.001, 0.001);
  ASSERT_TRUE(d.valid);
  EXPECT_NEAR(d.pose.position.x, 0.013, 1e-7);
  EXPECT_EQ(r.driver.counters().sequenceGaps, 0u);
  EXPECT_EQ(r.driver.counters().framesReceived, 4u);
  // 14 and 15 never arrived.
  r.wire.incoming.push_back(stateFrame(16, 0.016f));
  EXPECT_TRUE(r.driver.read(0.002, 0.001).valid);
  EXPECT_EQ(r.driver.counters().sequenceGaps, 2u);
}

TEST(AresDriver, SequenceWrapsAroundWithoutAGap) {
  Rig r;
  r.wire.incoming.push_back(stateFrame(0xFFFFFFFFu, 0.01f));
  r.driver.read(0.0, 0.001);
  r.wire.incoming.push_back(stateFrame(0, 0.01f));
  EXPECT_TRUE(r.driver.read(0.001, 0.001).valid);
  EXPECT_EQ(r.driver.counters().sequenceGaps, 0u);
}

TEST(AresDriver, CorruptFramesAreDroppedAndCounted) {
  Rig r;
  r.wire.incoming.push_back(stateFrame(1, 0.01f));
  r.driver.read(0.0, 0.001);
  auto bad = stateFrame(2, 0.5f);
  bad[13] ^= 0x40;  // a flipped bit in the position
  r.wire.incoming.push_back(bad);
  const DeviceReading d = r.driver.read(0.001, 0.001);
  EXPECT_FALSE(d.valid);
  EXPECT_NEAR(d.pose.position.x, 0.01, 1e-7) << "the corrupt pose must not be used";
  auto shortFrame = stateFrame(3, 0.01f);
  shortFrame.resize(20);
  r.wire.incoming.push_back(shortFrame);
  EXPECT_FALSE(r.driver.read(0.002, 0.001).valid);
  EXPECT_EQ(r.driver.counters().checksumErrors, 2u);
  EXPECT_FALSE(r.driver.failed());
  r.wire.incoming.push_back(stateFrame(4, 0.02f));
  EXPECT_TRUE(r.driver.read(0.003, 0.001).valid);
  EXPECT_EQ(r.driver.counters().sequenceGaps, 2u);  // 2 and 3 never decoded
}

TEST(AresDriver, UnhomedDeviceOrBadQuaternionIsNotValid) {
  Rig r;
  r.wire.incoming.push_back(stateFrame(1, 0.01f, 0, ares::kStatusNotHomed));
  EXPECT_FALSE(r.driver.read(0.0, 0.001).valid);
  ares::StateFrame s;
  s.sequence = 2;
  s.orientation = {0.f, 0.f, 0.f, 0.f};
  std::vector<std::uint8_t> b(ares::kStateFrameSize);
  ares::encode(s, b);
  r.wire.incoming.push_back(b);
  EXPECT_FALSE(r.driver.read(0.001, 0.001).valid);
  EXPECT_EQ(r.driver.deviceStatus(), 0u);
}

TEST(AresDriver, OtherProtocolVersionFailsWithAClearMessage) {
  Rig r;
  auto b = stateFrame(1, 0.0f);
  b[2] = 7;
  const std::uint32_t c = ares::crc32({b.data(), 60});
  for (int i = 0; i < 4; ++i) b[60 + i] = static_cast<std::uint8_t>(c >> (8 * i));
  r.wire.incoming.push_back(b);
  r.driver.read(0.0, 0.001);
  ASSERT_TRUE(r.driver.failed());
  EXPECT_NE(r.driver.failure().find("version 7"), std::string::npos) << r.driver.failure();
}

TEST(AresDriver, WritesSequencedEnabledCommands) {
  Rig r;
  r.driver.write({1.0, -2.0, 0.5}, {0.01, 0.0, -0.02});
  r.driver.write({0.0, 0.0, 3.0}, {0.0, 0.0, 0.0});
  ASSERT_EQ(r.wire.sent.size(), 2u);
  const ares::CommandFrame a = decodeCommand(r.wire.sent[0]), b = decodeCommand(r.wire.sent[1]);
  EXPECT_EQ(a.sequence, 1u);
  EXPECT_EQ(b.sequence, 2u);
  EXPECT_EQ(a.force[1], -2.0f);
  EXPECT_EQ(a.torque[2], -0.02f);
  EXPECT_EQ(a.flags, ares::kCommandEnable);
  EXPECT_EQ(b.force[2], 3.0f);
  EXPECT_EQ(r.driver.counters().framesSent, 2u);
}

TEST(AresDriver, NeverSendsNaNOrUnclampedForces) {
  Rig r;  // limits 10 N, 0.5 N·m
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.driver.write({nan, 0.0, 1.0}, {0.0, 0.0, 0.1});
  r.driver.write({0.0, 300.0, 400.0}, {0.0, 0.0, 2.0});
  ASSERT_EQ(r.wire.sent.size(), 2u);
  const ares::CommandFrame a = decodeCommand(r.wire.sent[0]), b = decodeCommand(r.wire.sent[1]);
  EXPECT_EQ(a.force, (std::array<float, 3>{0.f, 0.f, 0.f}));
  EXPECT_NEAR(b.force[1], 6.0f, 1e-5);
  EXPECT_NEAR(b.force[2], 8.0f, 1e-5);
  EXPECT_NEAR(b.torque[2], 0.5f, 1e-6);
}

TEST(AresDriver, SendFailuresAreCountedThenFatal) {
  FakeWire w;
  AresDriverOptions o;
  o.maxConsecutiveErrors = 5;
  AresDriver d(std::make_unique<FakeTransport>(w), o);
  w.failSends = 4;
  for (int i = 0; i < 4; ++i) d.write({}, {});
  EXPECT_EQ(d.counters().transferErrors, 4u);
  EXPECT_FALSE(d.failed());
  d.write({}, {});  // succeeds: the run of errors ends
  w.failSends = 5;
  for (int i = 0; i < 5; ++i) d.write({}, {});
  ASSERT_TRUE(d.failed());
  EXPECT_NE(d.failure().find("5 USB transfers failed in a row"), std::string::npos) << d.failure();
}

TEST(AresDriver, UnplugFailsWithAMessageNamingTheDevice) {
  Rig r;
  r.wire.incoming.push_back(stateFrame(1, 0.01f));
  r.driver.read(0.0, 0.001);
  r.wire.connected = false;
  const DeviceReading d = r.driver.read(0.001, 0.001);
  EXPECT_FALSE(d.valid);
  ASSERT_TRUE(r.driver.failed());
  EXPECT_NE(r.driver.failure().find("1209:0001"), std::string::npos) << r.driver.failure();
  EXPECT_NE(r.driver.failure().find("unplugged"), std::string::npos) << r.driver.failure();
  // After failing, nothing more is attempted and stop() is still safe.
  const auto sentBefore = r.wire.sent.size();
  r.driver.write({1, 0, 0}, {});
  r.driver.stop();
  EXPECT_EQ(r.wire.sent.size(), sentBefore);
  EXPECT_TRUE(r.wire.closed);
}

TEST(AresDriver, StopSendsDisabledZeroFramesThenReleases) {
  Rig r;
  r.driver.write({1.0, 2.0, 3.0}, {0.1, 0.1, 0.1});
  r.driver.stop();
  ASSERT_EQ(r.wire.sent.size(), 1u + AresDriverOptions{}.stopFrames);
  std::uint32_t seq = 1;
  for (std::size_t i = 1; i < r.wire.sent.size(); ++i) {
    const ares::CommandFrame c = decodeCommand(r.wire.sent[i]);
    EXPECT_EQ(c.sequence, ++seq);
    EXPECT_EQ(c.force, (std::array<float, 3>{0.f, 0.f, 0.f}));
    EXPECT_EQ(c.torque, (std::array<float, 3>{0.f, 0.f, 0.f}));
    EXPECT_EQ(c.flags & ares::kCommandEnable, 0);
  }
  EXPECT_TRUE(r.wire.closed);
  r.driver.stop();  // idempotent
  r.driver.write({1, 0, 0}, {});
  EXPECT_EQ(r.wire.sent.size(), 1u + AresDriverOptions{}.stopFrames);
}
