#include "vm_ffs.hpp"

#include <fcntl.h>
#include <linux/usb/functionfs.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace foveal::vmtest::ffs {
namespace {

template <class T>
void put(std::vector<std::uint8_t>& out, const T& v) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
  out.insert(out.end(), p, p + sizeof v);
}

/// One speed's descriptors; `count` gets how many.
std::vector<std::uint8_t> speed_descriptors(const std::vector<Interface>& interfaces, bool high, std::uint32_t& count) {
  std::vector<std::uint8_t> out;
  std::uint8_t number = 0;
  count = 0;
  for (const Interface& i : interfaces) {
    usb_interface_descriptor itf{};
    itf.bLength = USB_DT_INTERFACE_SIZE;
    itf.bDescriptorType = USB_DT_INTERFACE;
    itf.bInterfaceNumber = i.number;
    itf.bAlternateSetting = i.alt;
    itf.bNumEndpoints = static_cast<std::uint8_t>(i.endpoints.size());
    itf.bInterfaceClass = i.cls;
    itf.iInterface = 1;
    put(out, itf);
    ++count;
    if (!i.class_descriptor.empty()) {
      out.insert(out.end(), i.class_descriptor.begin(), i.class_descriptor.end());
      ++count;
    }
    for (const Endpoint& e : i.endpoints) {
      usb_endpoint_descriptor_no_audio ep{};
      ep.bLength = USB_DT_ENDPOINT_SIZE;
      ep.bDescriptorType = USB_DT_ENDPOINT;
      ep.bEndpointAddress = static_cast<std::uint8_t>(++number | (e.in ? USB_DIR_IN : USB_DIR_OUT));
      ep.bmAttributes = e.type;
      ep.wMaxPacketSize = high ? e.hs_packet : e.fs_packet;
      ep.bInterval = high ? e.hs_interval : e.fs_interval;
      put(out, ep);
      ++count;
    }
  }
  return out;
}

}  // namespace

std::vector<std::uint8_t> descriptors(const std::vector<Interface>& interfaces) {
  std::uint32_t fs_count = 0, hs_count = 0;
  const auto fs = speed_descriptors(interfaces, false, fs_count), hs = speed_descriptors(interfaces, true, hs_count);
  usb_functionfs_descs_head_v2 head{};
  head.magic = FUNCTIONFS_DESCRIPTORS_MAGIC_V2;
  head.flags = FUNCTIONFS_HAS_FS_DESC | FUNCTIONFS_HAS_HS_DESC;
  head.length = static_cast<std::uint32_t>(sizeof head + 2 * sizeof(std::uint32_t) + fs.size() + hs.size());
  std::vector<std::uint8_t> out;
  put(out, head);
  put(out, fs_count);
  put(out, hs_count);
  out.insert(out.end(), fs.begin(), fs.end());
  out.insert(out.end(), hs.begin(), hs.end());
  return out;
}

std::vector<std::uint8_t> strings(const std::string& name) {
  std::vector<std::uint8_t> out;
  usb_functionfs_strings_head head{};
  head.magic = FUNCTIONFS_STRINGS_MAGIC;
  head.str_count = 1;
  head.lang_count = 1;
  head.length = static_cast<std::uint32_t>(sizeof head + 2 + name.size() + 1);
  put(out, head);
  const std::uint16_t lang = 0x0409;
  put(out, lang);
  out.insert(out.end(), name.begin(), name.end());
  out.push_back(0);
  return out;
}

int open_ep0(const std::string& dir, const std::vector<Interface>& interfaces, const std::string& name) {
  const int ep0 = ::open((dir + "/ep0").c_str(), O_RDWR);
  if (ep0 < 0) {
    std::printf("ffs: cannot open %s/ep0: %s\n", dir.c_str(), std::strerror(errno));
    return -1;
  }
  const auto d = descriptors(interfaces), s = strings(name);
  if (::write(ep0, d.data(), d.size()) < 0 || ::write(ep0, s.data(), s.size()) < 0) {
    std::printf("ffs: FunctionFS refused the descriptors of %s: %s\n", dir.c_str(), std::strerror(errno));
    ::close(ep0);
    return -1;
  }
  return ep0;
}

void serve_ep0(int ep0, const std::atomic<bool>& stop, const Handlers& h) {
  while (!stop.load()) {
    pollfd p{ep0, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    usb_functionfs_event ev[4];
    const ssize_t n = ::read(ep0, ev, sizeof ev);
    for (ssize_t i = 0; n > 0 && i < n / static_cast<ssize_t>(sizeof ev[0]); ++i) {
      if ((ev[i].type == FUNCTIONFS_ENABLE || ev[i].type == FUNCTIONFS_DISABLE) && h.enabled)
        h.enabled(ev[i].type == FUNCTIONFS_ENABLE);
      if (ev[i].type != FUNCTIONFS_SETUP) continue;
      const usb_ctrlrequest& c = ev[i].u.setup;
      if (c.bRequestType & USB_DIR_IN) {
        auto data = h.in ? h.in(c) : std::nullopt;
        if (!data) {
          (void)::read(ep0, nullptr, 0);  // a read on an IN request stalls it
          continue;
        }
        data->resize(std::min<std::size_t>(data->size(), c.wLength));
        (void)::write(ep0, data->data(), data->size());
      } else {
        std::vector<std::uint8_t> data(c.wLength);
        const ssize_t got = ::read(ep0, data.data(), data.size());  // the data stage; acknowledges it
        data.resize(got > 0 ? static_cast<std::size_t>(got) : 0);
        if (h.out) h.out(c, data);
      }
    }
  }
}

bool write_all(int fd, const std::vector<std::uint8_t>& data) {
  return ::write(fd, data.data(), data.size()) == static_cast<ssize_t>(data.size());
}

}  // namespace foveal::vmtest::ffs
