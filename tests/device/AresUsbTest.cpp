// End to end through real libusb: an AresDevice node opens an ARES device
// that umockdev emulates (tests/data/umockdev/ares.umockdev, ares.ioctl).
// Run only under umockdev-run (see tests/CMakeLists.txt); each test gets its
// own umockdev-run, so the scripted dialogue starts afresh.
#include <gtest/gtest.h>

#include <cstdlib>

#include "millsim/devices/AresDevice.h"

using namespace millsim;

namespace {

bool underUmockdev() { return std::getenv("UMOCKDEV_DIR") != nullptr; }

std::unique_ptr<DeviceDriver> open(const std::string& serial) {
  AresDevice node;  // 1209:0001
  node.serialNumber.set(serial);
  return node.openDriver({});
}

}  // namespace

// The dialogue of tests/data/umockdev/make-ares-scripts.py: three state
// frames (sequence 1, 2, 5), each answered by a command; a corrupt frame;
// then the device is unplugged.
TEST(AresUsb, StreamsThenReportsTheUnplug) {
  ASSERT_TRUE(underUmockdev()) << "run this test under umockdev-run";
  std::unique_ptr<DeviceDriver> d = open("ARES-TEST-0001");  // serial from sysfs

  const double dt = 0.001;
  DeviceReading r = d->read(0.0, dt);
  ASSERT_TRUE(r.valid) << d->failure();
  EXPECT_NEAR(r.pose.position.x, 0.010, 1e-7);
  EXPECT_NEAR(r.pose.position.y, 0.020, 1e-7);
  EXPECT_NEAR(r.pose.position.z, 0.030, 1e-7);
  EXPECT_EQ(r.pose.orientation.w, 1.0);
  EXPECT_FALSE(r.button);
  d->write({0.5, -1.25, 2.0}, {0.0, 0.125, -0.25});

  r = d->read(dt, dt);
  ASSERT_TRUE(r.valid) << d->failure();
  EXPECT_NEAR(r.pose.position.x, 0.011, 1e-7);
  EXPECT_EQ(r.pose.orientation.x, 1.0);
  EXPECT_TRUE(r.button);
  d->write({1.0, 0.0, -3.5}, {0.0625, 0.0, 0.0});

  r = d->read(2 * dt, dt);
  ASSERT_TRUE(r.valid) << d->failure();
  EXPECT_NEAR(r.pose.position.y, 0.021, 1e-7);
  EXPECT_NEAR(r.pose.orientation.w, 0.5, 1e-7);
  d->write({-2.0, 4.0, 0.25}, {0.0, -0.5, 0.0});

  r = d->read(3 * dt, dt);  // the corrupt frame
  EXPECT_FALSE(r.valid);
  EXPECT_FALSE(d->failed()) << d->failure();
  d->write({0.0, 0.0, 1.0}, {0.0, 0.0, 0.0});

  r = d->read(4 * dt, dt);  // unplugged
  EXPECT_FALSE(r.valid);
  ASSERT_TRUE(d->failed());
  EXPECT_NE(d->failure().find("ARES device 1209:0001 serial 'ARES-TEST-0001'"), std::string::npos) << d->failure();
  EXPECT_NE(d->failure().find("unplugged"), std::string::npos) << d->failure();

  const DeviceCounters c = d->counters();
  EXPECT_EQ(c.framesReceived, 4u);
  EXPECT_EQ(c.framesSent, 4u);  // every command matched the script byte for byte
  EXPECT_EQ(c.sequenceGaps, 2u);  // 3 and 4
  EXPECT_EQ(c.checksumErrors, 1u);
  EXPECT_EQ(c.transferErrors, 0u);
  d->stop();  // the device is gone: no frames, just the release
  std::printf("%s\n", d->failure().c_str());
}

TEST(AresUsb, NoMatchingDeviceSaysWhatWasLookedForAndWhatWasSeen) {
  ASSERT_TRUE(underUmockdev()) << "run this test under umockdev-run";
  AresDevice node;
  node.productId.set(0x0002);
  node.serialNumber.set("ARES-42");
  try {
    node.openDriver({});
    FAIL() << "opened a device that does not exist";
  } catch (const DeviceError& e) {
    const std::string m = e.what();
    std::printf("%s\n", m.c_str());
    EXPECT_NE(m.find("ARES device 1209:0002"), std::string::npos) << m;
    EXPECT_NE(m.find("ARES-42"), std::string::npos) << m;
    EXPECT_NE(m.find("1209:0001 \"ARES haptic device (emulated)\""), std::string::npos)
        << "the emulated device should be listed as seen: " << m;
  }
}

TEST(AresUsb, WrongSerialNumberIsRejectedNamingTheOneFound) {
  ASSERT_TRUE(underUmockdev()) << "run this test under umockdev-run";
  try {
    open("ARES-TEST-9999");
    FAIL() << "opened a device with another serial number";
  } catch (const DeviceError& e) {
    const std::string m = e.what();
    std::printf("%s\n", m.c_str());
    EXPECT_NE(m.find("with serial number 'ARES-TEST-9999'"), std::string::npos) << m;
    EXPECT_NE(m.find("its serial number is 'ARES-TEST-0001'"), std::string::npos) << m;
  }
}

// Run with ares-stop.ioctl: the script ends with three zero, disabled
// commands, so stop() must send exactly those (umockdev rejects any other bytes).
TEST(AresUsb, StopSendsZeroCommands) {
  ASSERT_TRUE(underUmockdev()) << "run this test under umockdev-run";
  std::unique_ptr<DeviceDriver> d = open("");
  ASSERT_TRUE(d->read(0.0, 0.001).valid) << d->failure();
  d->write({0.5, -1.25, 2.0}, {0.0, 0.125, -0.25});
  d->stop();
  EXPECT_FALSE(d->failed()) << d->failure();
  EXPECT_EQ(d->counters().framesSent, 4u);
  EXPECT_EQ(d->counters().transferErrors, 0u);
}
