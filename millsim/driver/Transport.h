#pragma once
// Transport: how a device driver moves whole frames to and from hardware.
// UsbTransport implements it over libusb; tests use a fake. Only the haptic
// thread calls it once the driver is open; every call is bounded by its
// timeout.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace millsim {

enum class TransferStatus {
  Ok,            // a frame was sent, or received (length bytes)
  Timeout,       // nothing arrived / could not send within the timeout
  Disconnected,  // the device is gone; every later call returns this too
  Error,         // this transfer failed (stall, overflow, I/O error); the next may work
};

struct TransferResult {
  TransferStatus status = TransferStatus::Timeout;
  std::size_t length = 0;  // bytes received (receive only)
};

class Transport {
public:
  virtual ~Transport() = default;

  // Sends one frame.
  virtual TransferResult send(std::span<const std::uint8_t> frame, std::chrono::microseconds timeout) = 0;
  // Receives the newest frame the device offers into `buffer`, waiting at most
  // `timeout`, and discards older ones still waiting (reported through
  // `discarded` so gaps can be told from drops). Timeout 0: only a frame
  // already waiting.
  virtual TransferResult receiveNewest(std::span<std::uint8_t> buffer, std::chrono::microseconds timeout,
                                       std::uint64_t& discarded) = 0;
  virtual bool connected() const = 0;
  // For messages: e.g. "USB 1209:0001 serial A1B2 on bus 1 device 2".
  virtual std::string describe() const = 0;
  // Releases the device (idempotent); send/receive fail with Disconnected after it.
  virtual void close() = 0;
};

}  // namespace millsim
