#pragma once
// The ARES wire protocol (docs/ares-protocol.md): fixed-size little-endian
// frames with a magic, a version, a sequence number and a CRC-32 trailer.
// Encoding and decoding work on caller-owned byte spans: no allocation, and
// the decoder never reads outside the span it is given.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace millsim::ares {

inline constexpr std::uint16_t kMagic = 0x5241;  // bytes 'A' 'R' on the wire
inline constexpr std::uint8_t kVersion = 1;
inline constexpr std::uint8_t kTypeState = 0x01;    // device → host, EP 0x81
inline constexpr std::uint8_t kTypeCommand = 0x02;  // host → device, EP 0x01
inline constexpr std::size_t kStateFrameSize = 64;
// Device rule 4: with no valid command for this long the device ramps its
// output to zero; until then it applies the last one.
inline constexpr double kDeviceWatchdogSeconds = 0.010;
inline constexpr std::size_t kCommandFrameSize = 40;
inline constexpr std::size_t kMaxPacketSize = 64;  // wMaxPacketSize of both endpoints

// Development identity: the pid.codes test VID:PID, for in-house testing only
// (a shipped device needs its own PID).
inline constexpr std::uint16_t kDevVendorId = 0x1209;
inline constexpr std::uint16_t kDevProductId = 0x0001;
inline constexpr std::uint8_t kInterfaceNumber = 0;
inline constexpr std::uint8_t kEndpointIn = 0x81;
inline constexpr std::uint8_t kEndpointOut = 0x01;
// The device zeroes its output when no valid command arrived for this long.
inline constexpr std::uint32_t kDeviceWatchdogMs = 10;

// State frame bits.
enum Buttons : std::uint16_t { kButtonMain = 1u << 0 };
enum Status : std::uint16_t {
  kStatusEStop = 1u << 0,          // emergency stop pressed: motors unpowered
  kStatusOverTemperature = 1u << 1,
  kStatusOutputEnabled = 1u << 2,  // the device is applying commanded wrenches
  kStatusWatchdogTripped = 1u << 3,  // no valid command for kDeviceWatchdogMs
  kStatusNotHomed = 1u << 4,       // pose not calibrated yet: do not trust it
};
// Command frame bits.
enum CommandFlags : std::uint16_t { kCommandEnable = 1u << 0 };

struct StateFrame {
  std::uint32_t sequence = 0;
  std::uint32_t deviceTimeUs = 0;     // device clock, wraps after 2^32 µs
  std::array<float, 3> position{};    // burr centre, device base frame (m)
  std::array<float, 4> orientation{1.f, 0.f, 0.f, 0.f};  // unit quaternion w, x, y, z
  std::uint16_t buttons = 0;
  std::uint16_t status = 0;
  std::uint32_t lastCommandSequence = 0;  // newest valid command the device applied
};

struct CommandFrame {
  std::uint32_t sequence = 0;
  std::array<float, 3> force{};   // N, device base frame
  std::array<float, 3> torque{};  // N·m about the burr centre
  std::uint16_t flags = 0;
};

enum class DecodeError {
  None,
  Length,    // not exactly the frame size
  Magic,
  Version,   // a protocol version this host does not speak
  Type,      // a command frame where a state frame belongs or vice versa
  Checksum,
  NotFinite, // a NaN or Inf in a float field
};
const char* describe(DecodeError e);

// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320, as zlib's crc32()).
std::uint32_t crc32(std::span<const std::uint8_t> bytes);

// Encoders write exactly the frame size into `out` (which must be at least
// that large) and return the bytes written, or 0 if `out` is too small.
std::size_t encode(const StateFrame& f, std::span<std::uint8_t> out);
std::size_t encode(const CommandFrame& f, std::span<std::uint8_t> out);

DecodeError decode(std::span<const std::uint8_t> in, StateFrame& out);
DecodeError decode(std::span<const std::uint8_t> in, CommandFrame& out);

// The version byte of a frame with a valid magic, or 0: lets the host say which
// version a device speaks when decoding fails with DecodeError::Version.
std::uint8_t peekVersion(std::span<const std::uint8_t> in);

}  // namespace millsim::ares
