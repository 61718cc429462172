#pragma once
// UsbTransport: a Transport over libusb-1.0 interrupt endpoints (the ARES
// protocol's EP 0x81 IN and EP 0x01 OUT by default). One transfer is in
// flight at a time, each bounded by its timeout; the two libusb transfers
// and their buffers are allocated once at open.
#include <cstdint>
#include <memory>
#include <string>

#include "millsim/driver/Transport.h"

namespace millsim {

struct UsbMatch {
  std::uint16_t vendorId = 0;
  std::uint16_t productId = 0;
  std::string serialNumber;  // empty: any
  std::string deviceName = "USB device";  // for messages, e.g. "ARES device"
  std::uint8_t interfaceNumber = 0;
  std::uint8_t endpointIn = 0x81;
  std::uint8_t endpointOut = 0x01;
};

class UsbTransport final : public Transport {
public:
  // Finds, opens and claims the first device that matches. Throws DeviceError
  // saying what was looked for and listing the USB devices that were seen.
  static std::unique_ptr<UsbTransport> open(const UsbMatch& match);
  ~UsbTransport() override;

  TransferResult send(std::span<const std::uint8_t> frame, std::chrono::microseconds timeout) override;
  // The device keeps no queue of state frames (docs/ares-protocol.md): one IN
  // transfer returns the newest, so nothing is ever discarded here, and a
  // zero timeout returns Timeout at once without a transfer.
  TransferResult receiveNewest(std::span<std::uint8_t> buffer, std::chrono::microseconds timeout,
                               std::uint64_t& discarded) override;
  bool connected() const override { return connected_; }
  std::string describe() const override { return description_; }
  void close() override;

  struct Impl;

private:
  explicit UsbTransport(std::unique_ptr<Impl> impl, std::string description);
  std::unique_ptr<Impl> impl_;
  std::string description_;
  bool connected_ = true;
};

}  // namespace millsim
