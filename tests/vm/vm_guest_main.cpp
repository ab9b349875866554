#include <dirent.h>

#include <cstdlib>
#include <fstream>
#include <iterator>

#include "foveal/drivers/hid/report_descriptor.hpp"
#include "vm_guest.hpp"

namespace foveal::vmtest {

int count_open_fds() {
  int n = 0;
  if (DIR* d = ::opendir("/proc/self/fd")) {
    while (const dirent* e = ::readdir(d))
      if (e->d_name[0] != '.') ++n;
    ::closedir(d);
  }
  return n - 1;  // the directory stream's own descriptor
}

int run_hex2bin(const std::string& in, const std::string& out) {
  std::ifstream f(in);
  const std::string text{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
  auto bytes = hid::parse_hex_bytes(text);
  if (!bytes || bytes->empty()) {
    std::fprintf(stderr, "hex2bin: %s: %s\n", in.c_str(), bytes ? "empty" : bytes.error().message.c_str());
    return 2;
  }
  std::ofstream o(out, std::ios::binary);
  o.write(reinterpret_cast<const char*>(bytes->data()), static_cast<std::streamsize>(bytes->size()));
  return o ? 0 : 1;
}

}  // namespace foveal::vmtest

int main(int argc, char** argv) {
  using namespace foveal::vmtest;
  const std::string cmd = argc > 1 ? argv[1] : "";
  auto arg = [&](int i, const char* def) { return argc > i ? std::string(argv[i]) : std::string(def); };
  if (cmd == "feed") return run_feed(arg(2, "/dev/hidg0"));
  if (cmd == "probe") return run_probe(std::atoi(arg(2, "1000").c_str()), std::atof(arg(3, "60").c_str()));
  if (cmd == "replug") return run_replug(arg(2, ""), arg(3, "dummy_udc.0"), std::atoi(arg(4, "20").c_str()));
  if (cmd == "uhid") return run_uhid();
  if (cmd == "verify-log") return run_verify_log(arg(2, ""), std::atoi(arg(3, "100").c_str()), arg(4, "record_replay"));
#ifdef FOVEAL_VM_HAVE_USB
  if (cmd == "psvr2-gadget") return run_psvr2_gadget(arg(2, "/dev/ffs-gaze"), arg(3, "") == "--pose");
  if (cmd == "vive-gadget") return run_vive_gadget(arg(2, "/dev/ffs-vive"));
  if (cmd == "hmd-selftest") return run_hmd_selftest();
  if (cmd == "hmd-probe") return run_hmd_probe(arg(2, "psvr2"));
  if (cmd == "hmd" && argc > 7 && std::string(argv[6]) == "--")
    return run_hmd(argv[2], argv[3], argv[4], argv[5], std::vector<std::string>(argv + 7, argv + argc));
  if (cmd == "psvr2-probe") return run_psvr2_probe(std::atoi(arg(2, "500").c_str()), std::atof(arg(3, "30").c_str()));
#endif
  if (cmd == "hex2bin") return run_hex2bin(arg(2, ""), arg(3, ""));
  if (cmd == "live" && argc > 7 && std::string(argv[6]) == "--")
    return run_live(argv[2], argv[3], argv[4], argv[5], std::vector<std::string>(argv + 7, argv + argc));
  std::fprintf(stderr,
               "usage: foveal_vm_guest feed NODE | probe MIN_REPORTS TIMEOUT_S | replug UDC_FILE UDC_NAME CYCLES |\n"
               "       uhid | verify-log LOG MIN_SAMPLES [NAME] | psvr2-gadget FFS_DIR [--pose] | psvr2-probe MIN_SAMPLES TIMEOUT_S |\n"
               "       vive-gadget FFS_DIR | hex2bin IN OUT | live hid|psvr2 UDC_FILE UDC_NAME OUT -- FOVEALD ARGS... |\n"
               "       hmd psvr2|vive UDC_FILE UDC_NAME OUT -- FOVEALD ARGS... | hmd-selftest |\n"
               "       hmd-probe psvr2|vive\n");
  return 2;
}
