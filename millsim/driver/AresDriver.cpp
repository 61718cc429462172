#include "millsim/driver/AresDriver.h"

#include <algorithm>
#include <cmath>

namespace millsim {

namespace {

// Scales v to at most `limit`; zero if anything is not finite.
glm::dvec3 safe(const glm::dvec3& v, double limit) {
  if (!isFinite(v)) return glm::dvec3(0.0);
  const double len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return len > limit ? v * (limit / len) : v;
}

}  // namespace

AresDriver::AresDriver(std::unique_ptr<Transport> transport, const AresDriverOptions& options)
    : transport_(std::move(transport)), options_(options), label_(transport_->describe()) {
  lastReading_.valid = false;
}

AresDriver::~AresDriver() {
  if (!stopped_) stop();
}

void AresDriver::fail(std::string message) {
  if (failed_) return;
  failed_ = true;
  failure_ = std::move(message);
}

DeviceReading AresDriver::read(double, double dt) {
  DeviceReading reading = lastReading_;
  reading.valid = false;  // until a fresh, good frame arrives
  if (failed_ || stopped_) return reading;

  const auto period = std::chrono::microseconds(
      dt > 0.0 && std::isfinite(dt) ? static_cast<std::int64_t>(dt * 1e6) : options_.readTimeout.count());
  std::uint64_t discarded = 0;
  const TransferResult r =
      transport_->receiveNewest(rx_, std::min(options_.readTimeout, period), discarded);
  switch (r.status) {
    case TransferStatus::Disconnected:
      fail(label_ + " was unplugged (or lost power): output zeroed, haptic loop stopped");
      return reading;
    case TransferStatus::Timeout: ++counters_.transferErrors; return reading;
    case TransferStatus::Error:
      ++counters_.transferErrors;
      if (++consecutiveErrors_ >= options_.maxConsecutiveErrors)
        fail(label_ + " stopped answering: " + std::to_string(consecutiveErrors_) + " USB transfers failed in a row");
      return reading;
    case TransferStatus::Ok: break;
  }
  consecutiveErrors_ = 0;
  counters_.framesReceived += 1 + discarded;

  ares::StateFrame f;
  const std::span<const std::uint8_t> bytes(rx_.data(), r.length);
  const ares::DecodeError e = ares::decode(bytes, f);
  if (e == ares::DecodeError::Version) {
    fail(label_ + " speaks ARES protocol version " + std::to_string(ares::peekVersion(bytes)) +
         "; this MillSim speaks version " + std::to_string(ares::kVersion) + " (update the firmware or MillSim)");
    return reading;
  }
  if (e != ares::DecodeError::None) {
    ++counters_.checksumErrors;  // any corrupt frame: length, magic, type, CRC, NaN
    return reading;
  }
  if (haveState_) {
    const std::uint32_t step = f.sequence - lastState_.sequence;  // modulo 2^32
    if (step == 0 || step > 0x80000000u) return reading;         // a repeat or an older frame: not fresh
    counters_.sequenceGaps += (step - 1) - std::min<std::uint64_t>(step - 1, discarded);
  }
  haveState_ = true;
  lastState_ = f;

  const glm::dquat q(f.orientation[0], f.orientation[1], f.orientation[2], f.orientation[3]);
  const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  // A pose the device itself distrusts, or a quaternion far from unit length, is not used.
  if ((f.status & ares::kStatusNotHomed) || !(norm > 0.5 && norm < 1.5)) return reading;
  reading.pose.position = glm::dvec3(f.position[0], f.position[1], f.position[2]);
  reading.pose.orientation = q / norm;
  reading.button = (f.buttons & ares::kButtonMain) != 0;
  reading.valid = true;
  lastReading_ = reading;
  return reading;
}

bool AresDriver::sendCommand(const glm::dvec3& force, const glm::dvec3& torque, std::uint16_t flags) {
  const glm::dvec3 fs = safe(force, options_.forceLimit), ts = safe(torque, options_.torqueLimit);
  ares::CommandFrame c;
  c.sequence = ++commandSequence_;
  c.force = {static_cast<float>(fs.x), static_cast<float>(fs.y), static_cast<float>(fs.z)};
  c.torque = {static_cast<float>(ts.x), static_cast<float>(ts.y), static_cast<float>(ts.z)};
  c.flags = flags;
  const std::size_t n = ares::encode(c, tx_);
  const TransferResult r = transport_->send(std::span<const std::uint8_t>(tx_.data(), n), options_.writeTimeout);
  switch (r.status) {
    case TransferStatus::Ok:
      ++counters_.framesSent;
      consecutiveErrors_ = 0;
      return true;
    case TransferStatus::Disconnected:
      fail(label_ + " was unplugged (or lost power): output zeroed, haptic loop stopped");
      return false;
    case TransferStatus::Timeout:
    case TransferStatus::Error:
      ++counters_.transferErrors;
      if (++consecutiveErrors_ >= options_.maxConsecutiveErrors)
        fail(label_ + " stopped answering: " + std::to_string(consecutiveErrors_) + " USB transfers failed in a row");
      return false;
  }
  return false;
}

void AresDriver::write(const glm::dvec3& force, const glm::dvec3& torque) {
  if (failed_ || stopped_) return;
  sendCommand(force, torque, ares::kCommandEnable);
}

void AresDriver::stop() {
  if (stopped_) return;
  // Zero output explicitly (the device's own watchdog would also do it after
  // kDeviceWatchdogMs), unless the device is already gone.
  if (transport_->connected())
    for (int i = 0; i < options_.stopFrames && transport_->connected(); ++i)
      sendCommand(glm::dvec3(0.0), glm::dvec3(0.0), 0);
  stopped_ = true;
  transport_->close();
}

}  // namespace millsim
