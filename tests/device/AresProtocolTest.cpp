// The ARES wire protocol: round trips, the documented byte layout, and
// rejection of corrupt frames (every single-bit flip, every truncation).
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "millsim/driver/AresProtocol.h"

using namespace millsim::ares;

namespace {

StateFrame sampleState() {
  StateFrame s;
  s.sequence = 0xA1B2C3D4u;
  s.deviceTimeUs = 123456789u;
  s.position = {0.0125f, -0.034f, 0.5f};
  s.orientation = {0.5f, 0.5f, -0.5f, 0.5f};
  s.buttons = kButtonMain;
  s.status = kStatusOutputEnabled | kStatusOverTemperature;
  s.lastCommandSequence = 77;
  return s;
}

CommandFrame sampleCommand() {
  CommandFrame c;
  c.sequence = 42;
  c.force = {1.5f, -2.25f, 9.75f};
  c.torque = {0.01f, -0.02f, 0.3f};
  c.flags = kCommandEnable;
  return c;
}

std::uint32_t le32(const std::uint8_t* p) { return p[0] | p[1] << 8 | p[2] << 16 | std::uint32_t(p[3]) << 24; }

}  // namespace

TEST(AresProtocol, Crc32IsTheIeeeCheckValue) {
  const char* s = "123456789";
  EXPECT_EQ(crc32({reinterpret_cast<const std::uint8_t*>(s), 9}), 0xCBF43926u);
}

TEST(AresProtocol, StateFrameRoundTrips) {
  std::array<std::uint8_t, kStateFrameSize> buf{};
  const StateFrame in = sampleState();
  ASSERT_EQ(encode(in, buf), kStateFrameSize);
  StateFrame out;
  ASSERT_EQ(decode(buf, out), DecodeError::None);
  EXPECT_EQ(out.sequence, in.sequence);
  EXPECT_EQ(out.deviceTimeUs, in.deviceTimeUs);
  EXPECT_EQ(out.position, in.position);
  EXPECT_EQ(out.orientation, in.orientation);
  EXPECT_EQ(out.buttons, in.buttons);
  EXPECT_EQ(out.status, in.status);
  EXPECT_EQ(out.lastCommandSequence, in.lastCommandSequence);
}

TEST(AresProtocol, CommandFrameRoundTrips) {
  std::array<std::uint8_t, kCommandFrameSize> buf{};
  const CommandFrame in = sampleCommand();
  ASSERT_EQ(encode(in, buf), kCommandFrameSize);
  CommandFrame out;
  ASSERT_EQ(decode(buf, out), DecodeError::None);
  EXPECT_EQ(out.sequence, in.sequence);
  EXPECT_EQ(out.force, in.force);
  EXPECT_EQ(out.torque, in.torque);
  EXPECT_EQ(out.flags, in.flags);
}

// The layout of docs/ares-protocol.md, byte by byte where it matters.
TEST(AresProtocol, StateFrameLayoutMatchesTheDocument) {
  std::array<std::uint8_t, kStateFrameSize> b{};
  encode(sampleState(), b);
  EXPECT_EQ(b[0], 'A');
  EXPECT_EQ(b[1], 'R');
  EXPECT_EQ(b[2], kVersion);
  EXPECT_EQ(b[3], kTypeState);
  EXPECT_EQ(le32(&b[4]), 0xA1B2C3D4u);
  EXPECT_EQ(b[4], 0xD4);  // little-endian
  EXPECT_EQ(le32(&b[8]), 123456789u);
  float x;
  std::memcpy(&x, &b[12], 4);  // x86 is little-endian, like the wire
  EXPECT_EQ(x, 0.0125f);
  std::memcpy(&x, &b[24], 4);
  EXPECT_EQ(x, 0.5f);  // w first
  EXPECT_EQ(b[40], kButtonMain);
  EXPECT_EQ(b[42], kStatusOutputEnabled | kStatusOverTemperature);
  EXPECT_EQ(le32(&b[44]), 77u);
  for (int i = 48; i < 60; ++i) EXPECT_EQ(b[i], 0) << "reserved byte " << i;
  EXPECT_EQ(le32(&b[60]), crc32({b.data(), 60}));
}

TEST(AresProtocol, CommandFrameLayoutMatchesTheDocument) {
  std::array<std::uint8_t, kCommandFrameSize> b{};
  encode(sampleCommand(), b);
  EXPECT_EQ(b[0], 'A');
  EXPECT_EQ(b[1], 'R');
  EXPECT_EQ(b[2], kVersion);
  EXPECT_EQ(b[3], kTypeCommand);
  EXPECT_EQ(le32(&b[4]), 42u);
  float f;
  std::memcpy(&f, &b[8], 4);
  EXPECT_EQ(f, 1.5f);
  std::memcpy(&f, &b[28], 4);
  EXPECT_EQ(f, 0.3f);
  EXPECT_EQ(b[32], kCommandEnable);
  EXPECT_EQ(b[34], 0);
  EXPECT_EQ(b[35], 0);
  EXPECT_EQ(le32(&b[36]), crc32({b.data(), 36}));
}

TEST(AresProtocol, EncodeRefusesASmallBuffer) {
  std::array<std::uint8_t, kStateFrameSize - 1> small{};
  EXPECT_EQ(encode(sampleState(), small), 0u);
  std::array<std::uint8_t, kCommandFrameSize - 1> smallC{};
  EXPECT_EQ(encode(sampleCommand(), smallC), 0u);
}

TEST(AresProtocol, EverySingleBitFlipIsRejected) {
  std::array<std::uint8_t, kStateFrameSize> good{};
  encode(sampleState(), good);
  for (std::size_t bit = 0; bit < 8 * good.size(); ++bit) {
    auto bad = good;
    bad[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
    StateFrame out;
    out.sequence = 999;
    const DecodeError e = decode(bad, out);
    EXPECT_NE(e, DecodeError::None) << "bit " << bit;
    EXPECT_EQ(out.sequence, 999u) << "output touched on a rejected frame, bit " << bit;
  }
  std::array<std::uint8_t, kCommandFrameSize> goodC{};
  encode(sampleCommand(), goodC);
  for (std::size_t bit = 0; bit < 8 * goodC.size(); ++bit) {
    auto bad = goodC;
    bad[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
    CommandFrame out;
    EXPECT_NE(decode(bad, out), DecodeError::None) << "bit " << bit;
  }
}

// Truncated copies live in exactly-sized heap buffers so that AddressSanitizer
// catches any read past the end.
TEST(AresProtocol, EveryTruncationAndExtensionIsRejected) {
  std::array<std::uint8_t, kStateFrameSize> good{};
  encode(sampleState(), good);
  for (std::size_t n = 0; n < good.size(); ++n) {
    std::vector<std::uint8_t> cut(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n));
    StateFrame out;
    EXPECT_NE(decode(cut, out), DecodeError::None) << "length " << n;
  }
  std::vector<std::uint8_t> longer(good.begin(), good.end());
  longer.push_back(0);
  StateFrame out;
  EXPECT_EQ(decode(longer, out), DecodeError::Length);
  EXPECT_EQ(decode(std::span<const std::uint8_t>(), out), DecodeError::Length);
}

TEST(AresProtocol, NamesTheReasonForARejection) {
  std::array<std::uint8_t, kStateFrameSize> b{};
  StateFrame out;
  encode(sampleState(), b);
  auto bad = b;
  bad[0] = 'X';
  EXPECT_EQ(decode(bad, out), DecodeError::Magic);
  bad = b;
  bad[20] ^= 1;
  EXPECT_EQ(decode(bad, out), DecodeError::Checksum);

  // A well-formed frame of another version (or type) with a valid CRC.
  auto reseal = [](std::array<std::uint8_t, kStateFrameSize> f) {
    const std::uint32_t c = crc32({f.data(), 60});
    for (int i = 0; i < 4; ++i) f[60 + i] = static_cast<std::uint8_t>(c >> (8 * i));
    return f;
  };
  bad = b;
  bad[2] = 2;
  EXPECT_EQ(decode(reseal(bad), out), DecodeError::Version);
  EXPECT_EQ(peekVersion(reseal(bad)), 2);
  bad = b;
  bad[3] = kTypeCommand;
  EXPECT_EQ(decode(reseal(bad), out), DecodeError::Type);
  // A NaN in the pose, even with a valid CRC.
  bad = b;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&bad[16], &nan, 4);
  EXPECT_EQ(decode(reseal(bad), out), DecodeError::NotFinite);
  EXPECT_STRNE(describe(DecodeError::Checksum), describe(DecodeError::Magic));
}

// Reported, not asserted: timing on a shared machine is not a test.
TEST(AresProtocol, EncodeDecodeCost) {
  std::array<std::uint8_t, kStateFrameSize> b{};
  StateFrame s = sampleState(), out;
  constexpr int kN = 200000;
  const auto t0 = std::chrono::steady_clock::now();
  std::uint32_t sum = 0;
  for (int i = 0; i < kN; ++i) {
    s.sequence = static_cast<std::uint32_t>(i);
    encode(s, b);
    sum += decode(b, out) == DecodeError::None ? out.sequence : 0;
  }
  const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / kN;
  EXPECT_GT(sum, 0u);
  RecordProperty("encode_decode_ns", std::to_string(ns));
  std::printf("state frame encode + decode: %.0f ns\n", ns);
}
