#include "millsim/driver/AresProtocol.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include <zlib.h>

namespace millsim::ares {

static_assert(std::endian::native == std::endian::little || std::endian::native == std::endian::big);
static_assert(sizeof(float) == 4 && std::numeric_limits<float>::is_iec559, "the wire format is IEEE 754 binary32");

namespace {

// Byte-wise little-endian access: correct on any host endianness and
// alignment, and compilers turn it into single loads/stores on x86.
void put16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
void put32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
void putF(std::uint8_t* p, float v) { put32(p, std::bit_cast<std::uint32_t>(v)); }
std::uint16_t get16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }
std::uint32_t get32(const std::uint8_t* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}
float getF(const std::uint8_t* p) { return std::bit_cast<float>(get32(p)); }

// Header: magic (2), version (1), type (1), sequence (4).
void putHeader(std::uint8_t* p, std::uint8_t type, std::uint32_t sequence) {
  put16(p, kMagic);
  p[2] = kVersion;
  p[3] = type;
  put32(p + 4, sequence);
}

// Magic, CRC, version, type, then length: a frame of any version keeps bytes
// 0–3 and its CRC-32 trailer, so a newer device is reported as a version
// mismatch rather than as garbage. Only then are fields read.
DecodeError checkFrame(std::span<const std::uint8_t> in, std::size_t size, std::uint8_t type) {
  if (in.size() < 8 || in.size() > kMaxPacketSize) return DecodeError::Length;
  const std::uint8_t* p = in.data();
  if (get16(p) != kMagic) return DecodeError::Magic;
  if (crc32(in.first(in.size() - 4)) != get32(p + in.size() - 4)) return DecodeError::Checksum;
  if (p[2] != kVersion) return DecodeError::Version;
  if (p[3] != type) return DecodeError::Type;
  if (in.size() != size) return DecodeError::Length;
  return DecodeError::None;
}

template <std::size_t N>
bool allFinite(const std::array<float, N>& a) {
  for (float v : a)
    if (!std::isfinite(v)) return false;
  return true;
}

// State frame offsets (docs/ares-protocol.md, "State frame").
constexpr std::size_t kSTime = 8, kSPos = 12, kSQuat = 24, kSButtons = 40, kSStatus = 42, kSLastCmd = 44,
                      kSReserved = 48, kSCrc = 60;
// Command frame offsets (docs/ares-protocol.md, "Command frame").
constexpr std::size_t kCForce = 8, kCTorque = 20, kCFlags = 32, kCReserved = 34, kCCrc = 36;
static_assert(kSCrc + 4 == kStateFrameSize && kCCrc + 4 == kCommandFrameSize);

}  // namespace

const char* describe(DecodeError e) {
  switch (e) {
    case DecodeError::None: return "ok";
    case DecodeError::Length: return "wrong frame length";
    case DecodeError::Magic: return "bad magic (not an ARES frame)";
    case DecodeError::Version: return "unsupported protocol version";
    case DecodeError::Type: return "unexpected frame type";
    case DecodeError::Checksum: return "CRC-32 mismatch";
    case DecodeError::NotFinite: return "NaN or Inf in a value";
  }
  return "unknown decode error";
}

std::uint32_t crc32(std::span<const std::uint8_t> bytes) {
  // zlib's table-driven CRC-32: the IEEE polynomial most MCU CRC units and
  // firmware libraries implement, and already linked into libmillsim.
  return static_cast<std::uint32_t>(::crc32(::crc32(0L, Z_NULL, 0), bytes.data(), static_cast<uInt>(bytes.size())));
}

std::size_t encode(const StateFrame& f, std::span<std::uint8_t> out) {
  if (out.size() < kStateFrameSize) return 0;
  std::uint8_t* p = out.data();
  putHeader(p, kTypeState, f.sequence);
  put32(p + kSTime, f.deviceTimeUs);
  for (int i = 0; i < 3; ++i) putF(p + kSPos + 4 * i, f.position[i]);
  for (int i = 0; i < 4; ++i) putF(p + kSQuat + 4 * i, f.orientation[i]);
  put16(p + kSButtons, f.buttons);
  put16(p + kSStatus, f.status);
  put32(p + kSLastCmd, f.lastCommandSequence);
  std::memset(p + kSReserved, 0, kSCrc - kSReserved);
  put32(p + kSCrc, crc32(out.first(kSCrc)));
  return kStateFrameSize;
}

std::size_t encode(const CommandFrame& f, std::span<std::uint8_t> out) {
  if (out.size() < kCommandFrameSize) return 0;
  std::uint8_t* p = out.data();
  putHeader(p, kTypeCommand, f.sequence);
  for (int i = 0; i < 3; ++i) putF(p + kCForce + 4 * i, f.force[i]);
  for (int i = 0; i < 3; ++i) putF(p + kCTorque + 4 * i, f.torque[i]);
  put16(p + kCFlags, f.flags);
  put16(p + kCReserved, 0);
  put32(p + kCCrc, crc32(out.first(kCCrc)));
  return kCommandFrameSize;
}

DecodeError decode(std::span<const std::uint8_t> in, StateFrame& out) {
  if (DecodeError e = checkFrame(in, kStateFrameSize, kTypeState); e != DecodeError::None) return e;
  const std::uint8_t* p = in.data();
  StateFrame f;
  f.sequence = get32(p + 4);
  f.deviceTimeUs = get32(p + kSTime);
  for (int i = 0; i < 3; ++i) f.position[i] = getF(p + kSPos + 4 * i);
  for (int i = 0; i < 4; ++i) f.orientation[i] = getF(p + kSQuat + 4 * i);
  f.buttons = get16(p + kSButtons);
  f.status = get16(p + kSStatus);
  f.lastCommandSequence = get32(p + kSLastCmd);
  if (!allFinite(f.position) || !allFinite(f.orientation)) return DecodeError::NotFinite;
  out = f;
  return DecodeError::None;
}

DecodeError decode(std::span<const std::uint8_t> in, CommandFrame& out) {
  if (DecodeError e = checkFrame(in, kCommandFrameSize, kTypeCommand); e != DecodeError::None) return e;
  const std::uint8_t* p = in.data();
  CommandFrame f;
  f.sequence = get32(p + 4);
  for (int i = 0; i < 3; ++i) f.force[i] = getF(p + kCForce + 4 * i);
  for (int i = 0; i < 3; ++i) f.torque[i] = getF(p + kCTorque + 4 * i);
  f.flags = get16(p + kCFlags);
  if (!allFinite(f.force) || !allFinite(f.torque)) return DecodeError::NotFinite;
  out = f;
  return DecodeError::None;
}

std::uint8_t peekVersion(std::span<const std::uint8_t> in) {
  if (in.size() < 3 || get16(in.data()) != kMagic) return 0;
  return in[2];
}

}  // namespace millsim::ares
