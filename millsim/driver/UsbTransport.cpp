#include "millsim/driver/UsbTransport.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <vector>

#include <libusb.h>

#include "millsim/driver/DeviceDriver.h"  // DeviceError

namespace millsim {

namespace {

std::string hex4(unsigned v) {
  char s[8];
  std::snprintf(s, sizeof s, "%04x", v & 0xffffu);
  return s;
}

std::string vidPid(std::uint16_t vid, std::uint16_t pid) { return hex4(vid) + ":" + hex4(pid); }

// Milliseconds for libusb (whose 0 means "wait forever"): at least 1.
unsigned timeoutMs(std::chrono::microseconds t) {
  return static_cast<unsigned>(std::max<std::int64_t>(1, t.count() / 1000));
}

// A string descriptor as ASCII ('?' for anything else), read with a short
// timeout of our own (libusb_get_string_descriptor_ascii waits up to 1 s).
// Empty if the device has none or does not answer.
std::string readString(libusb_device_handle* h, std::uint8_t index) {
  if (index == 0) return {};
  constexpr unsigned kTimeoutMs = 100;
  std::array<unsigned char, 255> buf{};
  int r = libusb_control_transfer(h, LIBUSB_ENDPOINT_IN, LIBUSB_REQUEST_GET_DESCRIPTOR, LIBUSB_DT_STRING << 8, 0,
                                  buf.data(), buf.size(), kTimeoutMs);
  if (r < 4 || buf[1] != LIBUSB_DT_STRING) return {};
  const std::uint16_t langId = static_cast<std::uint16_t>(buf[2] | (buf[3] << 8));
  r = libusb_control_transfer(h, LIBUSB_ENDPOINT_IN, LIBUSB_REQUEST_GET_DESCRIPTOR, (LIBUSB_DT_STRING << 8) | index,
                              langId, buf.data(), buf.size(), kTimeoutMs);
  if (r < 2 || buf[1] != LIBUSB_DT_STRING) return {};
  const int len = std::min<int>(r, buf[0]);
  std::string s;
  for (int i = 2; i + 1 < len; i += 2) {
    const unsigned c = buf[i] | (buf[i + 1] << 8);
    s += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  return s;
}

// A device's sysfs attribute ("product", "serial"), or empty. Linux names a
// USB device's sysfs node <bus>-<port>.<port>…, or usb<bus> for a root hub.
std::string sysfsAttribute(libusb_device* dev, const char* name) {
  std::array<std::uint8_t, 8> ports{};
  const int n = libusb_get_port_numbers(dev, ports.data(), static_cast<int>(ports.size()));
  std::string path = "/sys/bus/usb/devices/";
  if (n <= 0) {
    path += "usb" + std::to_string(libusb_get_bus_number(dev));
  } else {
    path += std::to_string(libusb_get_bus_number(dev)) + "-";
    for (int i = 0; i < n; ++i) path += (i ? "." : "") + std::to_string(ports[static_cast<std::size_t>(i)]);
  }
  path += std::string("/") + name;
  std::FILE* f = std::fopen(path.c_str(), "r");
  if (!f) return {};
  char buf[256] = {};
  const bool ok = std::fgets(buf, sizeof buf, f) != nullptr;
  std::fclose(f);
  if (!ok) return {};
  std::string s(buf);
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

// True if the active configuration has `iface` with interrupt endpoints
// `in` and `out`; otherwise says what it found in `why`.
bool hasEndpoints(libusb_device* dev, const UsbMatch& m, std::string& why) {
  libusb_config_descriptor* cfg = nullptr;
  if (int r = libusb_get_active_config_descriptor(dev, &cfg); r != 0) {
    why = std::string("its configuration descriptor could not be read (") + libusb_strerror(r) + ")";
    return false;
  }
  bool in = false, out = false, found = false;
  for (int i = 0; i < cfg->bNumInterfaces; ++i)
    for (int a = 0; a < cfg->interface[i].num_altsetting; ++a) {
      const libusb_interface_descriptor& d = cfg->interface[i].altsetting[a];
      if (d.bInterfaceNumber != m.interfaceNumber || d.bAlternateSetting != 0) continue;
      found = true;
      for (int e = 0; e < d.bNumEndpoints; ++e) {
        const libusb_endpoint_descriptor& ep = d.endpoint[e];
        const bool interrupt = (ep.bmAttributes & LIBUSB_TRANSFER_TYPE_MASK) == LIBUSB_TRANSFER_TYPE_INTERRUPT;
        in = in || (interrupt && ep.bEndpointAddress == m.endpointIn);
        out = out || (interrupt && ep.bEndpointAddress == m.endpointOut);
      }
    }
  libusb_free_config_descriptor(cfg);
  if (found && in && out) return true;
  char s[160];
  std::snprintf(s, sizeof s,
                found ? "interface %u lacks interrupt endpoint%s%s (expected IN 0x%02x and OUT 0x%02x)"
                      : "it has no interface %u%s%s (expected IN 0x%02x and OUT 0x%02x)",
                m.interfaceNumber, found && !in ? " IN" : "", found && !out ? " OUT" : "", m.endpointIn,
                m.endpointOut);
  why = s;
  return false;
}

void LIBUSB_CALL onTransferDone(libusb_transfer* t) { *static_cast<int*>(t->user_data) = 1; }

}  // namespace

struct UsbTransport::Impl {
  libusb_context* ctx = nullptr;
  libusb_device_handle* handle = nullptr;
  libusb_transfer* in = nullptr;
  libusb_transfer* out = nullptr;
  std::array<unsigned char, 64> inBuf{};
  std::array<unsigned char, 64> outBuf{};
  UsbMatch match;
  bool claimed = false;

  ~Impl() {
    if (in) libusb_free_transfer(in);
    if (out) libusb_free_transfer(out);
    if (handle) {
      if (claimed) libusb_release_interface(handle, match.interfaceNumber);
      libusb_close(handle);
    }
    if (ctx) libusb_exit(ctx);
  }

  // Submits `t` and handles events until it completes; its own timeout
  // bounds the wait (libusb cancels it when the timeout passes).
  TransferStatus run(libusb_transfer* t, int& actual) {
    int done = 0;
    t->user_data = &done;
    actual = 0;
    int r = libusb_submit_transfer(t);
    if (r == LIBUSB_ERROR_NO_DEVICE) return TransferStatus::Disconnected;
    if (r != 0) return TransferStatus::Error;
    while (!done) {
      r = libusb_handle_events_completed(ctx, &done);
      if (r < 0 && r != LIBUSB_ERROR_INTERRUPTED) {
        libusb_cancel_transfer(t);  // the completion (cancelled) still arrives
      }
    }
    actual = t->actual_length;
    switch (t->status) {
      case LIBUSB_TRANSFER_COMPLETED: return TransferStatus::Ok;
      case LIBUSB_TRANSFER_TIMED_OUT:
      case LIBUSB_TRANSFER_CANCELLED: return TransferStatus::Timeout;
      case LIBUSB_TRANSFER_NO_DEVICE: return TransferStatus::Disconnected;
      case LIBUSB_TRANSFER_STALL:
        libusb_clear_halt(handle, t->endpoint);
        return TransferStatus::Error;
      default: return TransferStatus::Error;
    }
  }
};

UsbTransport::UsbTransport(std::unique_ptr<Impl> impl, std::string description)
    : impl_(std::move(impl)), description_(std::move(description)) {}

UsbTransport::~UsbTransport() = default;

std::unique_ptr<UsbTransport> UsbTransport::open(const UsbMatch& m) {
  const std::string wanted = m.deviceName + " " + vidPid(m.vendorId, m.productId) +
                             (m.serialNumber.empty() ? std::string() : " with serial number '" + m.serialNumber + "'");
  auto impl = std::make_unique<Impl>();
  impl->match = m;
  if (int r = libusb_init(&impl->ctx); r != 0) {
    impl->ctx = nullptr;
    throw DeviceError("cannot look for " + wanted + ": libusb could not start (" + libusb_strerror(r) +
                      "); is a USB bus visible here (/dev/bus/usb)?");
  }
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(impl->ctx, &list);
  if (n < 0)
    throw DeviceError("cannot look for " + wanted + ": listing USB devices failed (" +
                      libusb_strerror(static_cast<int>(n)) + ")");
  struct ListGuard {
    libusb_device** l;
    ~ListGuard() { libusb_free_device_list(l, 1); }
  } guard{list};

  std::vector<std::string> seen, rejected;
  for (ssize_t i = 0; i < n; ++i) {
    libusb_device* dev = list[i];
    libusb_device_descriptor dd{};
    if (libusb_get_device_descriptor(dev, &dd) != 0) continue;
    const std::string where = "bus " + std::to_string(libusb_get_bus_number(dev)) + " device " +
                              std::to_string(libusb_get_device_address(dev));
    const bool idMatch = dd.idVendor == m.vendorId && dd.idProduct == m.productId;
    // Strings from sysfs first: no need to open (or have access to) devices
    // that are not ours, and no control transfer.
    std::string product = sysfsAttribute(dev, "product"), serial;
    if (!idMatch) {
      seen.push_back(vidPid(dd.idVendor, dd.idProduct) + (product.empty() ? "" : " \"" + product + "\"") + " (" +
                     where + ")");
      continue;
    }
    libusb_device_handle* h = nullptr;
    const int openResult = libusb_open(dev, &h);
    serial = sysfsAttribute(dev, "serial");
    if (openResult == 0) {
      if (product.empty()) product = readString(h, dd.iProduct);
      if (serial.empty()) serial = readString(h, dd.iSerialNumber);
    }
    seen.push_back(vidPid(dd.idVendor, dd.idProduct) + (product.empty() ? "" : " \"" + product + "\"") +
                   (serial.empty() ? "" : " serial '" + serial + "'") + " (" + where + ")");
    std::string why;
    if (openResult != 0)
      why = std::string("could not be opened (") + libusb_strerror(openResult) + ")" +
            (openResult == LIBUSB_ERROR_ACCESS ? ": give this user access to it, e.g. with a udev rule" : "");
    else if (!m.serialNumber.empty() && serial != m.serialNumber)
      why = serial.empty() ? "its serial number could not be read" : "its serial number is '" + serial + "'";
    else
      hasEndpoints(dev, m, why);
    if (why.empty()) {
      // Detach a kernel driver only if one is bound (vendor-specific
      // interfaces normally have none): libusb's auto-detach always issues
      // the disconnect ioctl and fails where that ioctl is not supported.
      if (libusb_kernel_driver_active(h, m.interfaceNumber) == 1)
        if (int r = libusb_detach_kernel_driver(h, m.interfaceNumber); r != 0 && r != LIBUSB_ERROR_NOT_FOUND)
          why = "its kernel driver could not be detached from interface " + std::to_string(m.interfaceNumber) + " (" +
                libusb_strerror(r) + ")";
    }
    if (why.empty()) {
      if (int r = libusb_claim_interface(h, m.interfaceNumber); r != 0)
        why = "interface " + std::to_string(m.interfaceNumber) + " could not be claimed (" + libusb_strerror(r) + ")" +
              (r == LIBUSB_ERROR_BUSY ? ": another program is using the device" : "");
    }
    if (!why.empty()) {
      if (h) libusb_close(h);
      rejected.push_back(vidPid(dd.idVendor, dd.idProduct) + " on " + where + ": " + why);
      continue;
    }
    impl->handle = h;
    impl->claimed = true;
    impl->in = libusb_alloc_transfer(0);
    impl->out = libusb_alloc_transfer(0);
    if (!impl->in || !impl->out) throw DeviceError("cannot open " + wanted + ": out of memory for USB transfers");
    libusb_fill_interrupt_transfer(impl->in, h, m.endpointIn, impl->inBuf.data(), impl->inBuf.size(), onTransferDone,
                                   nullptr, 1);
    libusb_fill_interrupt_transfer(impl->out, h, m.endpointOut, impl->outBuf.data(), 0, onTransferDone, nullptr, 1);
    const std::string description = m.deviceName + " " + vidPid(dd.idVendor, dd.idProduct) +
                                    (serial.empty() ? "" : " serial '" + serial + "'") + " on " + where;
    return std::unique_ptr<UsbTransport>(new UsbTransport(std::move(impl), description));
  }

  std::string msg = "no usable " + wanted + " found.";
  for (const std::string& r : rejected) msg += "\n  rejected " + r;
  msg += seen.empty() ? "\n  No USB devices were seen (is it plugged in and powered? Does this system show a USB bus?)"
                      : "\n  USB devices seen:";
  for (const std::string& s : seen) msg += "\n    " + s;
  throw DeviceError(msg);
}

TransferResult UsbTransport::send(std::span<const std::uint8_t> frame, std::chrono::microseconds timeout) {
  if (!connected_ || !impl_) return {TransferStatus::Disconnected, 0};
  if (frame.size() > impl_->outBuf.size()) return {TransferStatus::Error, 0};
  std::memcpy(impl_->outBuf.data(), frame.data(), frame.size());
  impl_->out->length = static_cast<int>(frame.size());
  impl_->out->timeout = timeoutMs(timeout);
  int actual = 0;
  TransferStatus s = impl_->run(impl_->out, actual);
  if (s == TransferStatus::Ok && actual != static_cast<int>(frame.size())) s = TransferStatus::Error;
  if (s == TransferStatus::Disconnected) connected_ = false;
  return {s, 0};
}

TransferResult UsbTransport::receiveNewest(std::span<std::uint8_t> buffer, std::chrono::microseconds timeout,
                                           std::uint64_t& discarded) {
  discarded = 0;
  if (!connected_ || !impl_) return {TransferStatus::Disconnected, 0};
  if (timeout.count() <= 0) return {TransferStatus::Timeout, 0};
  impl_->in->length = static_cast<int>(std::min(buffer.size(), impl_->inBuf.size()));
  impl_->in->timeout = timeoutMs(timeout);
  int actual = 0;
  const TransferStatus s = impl_->run(impl_->in, actual);
  if (s == TransferStatus::Disconnected) connected_ = false;
  if (s != TransferStatus::Ok) return {s, 0};
  if (actual == 0) return {TransferStatus::Timeout, 0};  // a zero-length packet: nothing new
  std::memcpy(buffer.data(), impl_->inBuf.data(), static_cast<std::size_t>(actual));
  return {TransferStatus::Ok, static_cast<std::size_t>(actual)};
}

void UsbTransport::close() {
  connected_ = false;
  impl_.reset();  // releases the interface, closes the device and exits libusb
}

}  // namespace millsim
