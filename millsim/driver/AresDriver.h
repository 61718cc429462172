#pragma once
// AresDriver: the haptic thread's side of an ARES device, speaking the ARES
// protocol (docs/ares-protocol.md) over any Transport. Frame buffers are
// members: no allocation per frame.
#include <array>
#include <memory>
#include <string>

#include "millsim/driver/AresProtocol.h"
#include "millsim/driver/DeviceDriver.h"
#include "millsim/driver/Transport.h"

namespace millsim {

struct AresDriverOptions {
  // Hard limits applied once more just before encoding (the safety layer has
  // already clamped; this guards against a caller that skipped it).
  double forceLimit = 10.0;   // N
  double torqueLimit = 0.5;   // N·m
  // Longest wait for a state frame in read(); never more than the frame period.
  std::chrono::microseconds readTimeout{1000};
  std::chrono::microseconds writeTimeout{1000};
  // This many failed transfers in a row (not timeouts) and the device counts as lost.
  int maxConsecutiveErrors = 100;
  // Zero-force frames stop() sends before releasing the device.
  int stopFrames = 3;
};

class AresDriver final : public DeviceDriver {
public:
  AresDriver(std::unique_ptr<Transport> transport, const AresDriverOptions& options);
  ~AresDriver() override;

  DeviceReading read(double t, double dt) override;
  void write(const glm::dvec3& force, const glm::dvec3& torque) override;
  bool failed() const override { return failed_; }
  std::string failure() const override { return failure_; }
  void stop() override;
  DeviceCounters counters() const override { return counters_; }

  // The newest state frame's status bits (ares::Status), for the log.
  std::uint16_t deviceStatus() const { return lastState_.status; }
  std::uint32_t commandSequence() const { return commandSequence_; }

private:
  void fail(std::string message);
  bool sendCommand(const glm::dvec3& force, const glm::dvec3& torque, std::uint16_t flags);

  std::unique_ptr<Transport> transport_;
  AresDriverOptions options_;
  std::string label_;  // the transport's description, for messages
  std::array<std::uint8_t, ares::kMaxPacketSize> rx_{};
  std::array<std::uint8_t, ares::kMaxPacketSize> tx_{};
  ares::StateFrame lastState_;
  DeviceReading lastReading_;
  DeviceCounters counters_;
  std::uint32_t commandSequence_ = 0;
  int consecutiveErrors_ = 0;
  bool haveState_ = false;
  bool failed_ = false;
  bool stopped_ = false;
  std::string failure_;
};

}  // namespace millsim
