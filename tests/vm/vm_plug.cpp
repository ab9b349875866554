// Plugging the emulated devices in and out (a gadget's UDC file) and seeing them come
// and go (sysfs), for the replug checks.
#include <dirent.h>
#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "vm_guest.hpp"

namespace foveal::vmtest {

bool write_udc(const std::string& file, const std::string& value) {
  const int fd = ::open(file.c_str(), O_WRONLY);
  if (fd < 0) return false;
  const std::string v = value + "\n";
  const bool ok = ::write(fd, v.data(), v.size()) == static_cast<ssize_t>(v.size());
  ::close(fd);
  return ok;
}

bool hidraw_present() {
  DIR* d = ::opendir("/sys/class/hidraw");
  if (d == nullptr) return false;
  bool any = false;
  while (const dirent* e = ::readdir(d)) any = any || e->d_name[0] != '.';
  ::closedir(d);
  return any;
}

bool usb_device_present(std::uint16_t vendor, std::uint16_t product) {
  DIR* d = ::opendir("/sys/bus/usb/devices");
  if (d == nullptr) return false;
  auto read_hex = [](const std::string& path) {
    std::ifstream f(path);
    unsigned v = 0;
    return (f >> std::hex >> v) ? static_cast<int>(v) : -1;
  };
  bool found = false;
  while (const dirent* e = ::readdir(d)) {
    const std::string dir = std::string("/sys/bus/usb/devices/") + e->d_name;
    if (e->d_name[0] != '.' && read_hex(dir + "/idVendor") == vendor && read_hex(dir + "/idProduct") == product) found = true;
  }
  ::closedir(d);
  return found;
}

}  // namespace foveal::vmtest
