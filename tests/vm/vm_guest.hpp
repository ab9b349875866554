#pragma once
// foveal_vm_guest: the programs that run inside the QEMU guest (tests/vm/init.sh).
// Each check prints one line "VMTEST <name> PASS|FAIL <details>" on the serial
// console; run_vm_tests.sh on the host reads them.
#include <cstdio>
#include <string>

namespace foveal::vmtest {

inline bool verdict(const char* name, bool pass, const std::string& details) {
  std::printf("VMTEST %s %s %s\n", name, pass ? "PASS" : "FAIL", details.c_str());
  std::fflush(stdout);
  return pass;
}

/// Open file descriptors of this process.
int count_open_fds();

int run_feed(const std::string& node);
int run_probe(int min_reports, double timeout_s);
int run_replug(const std::string& udc_file, const std::string& udc_name, int cycles);
int run_uhid();
int run_verify_log(const std::string& path, int min_samples, const std::string& name);
int run_psvr2_gadget(const std::string& ffs_dir);
int run_psvr2_probe(int min_samples, double timeout_s);
int run_hex2bin(const std::string& in, const std::string& out);

}  // namespace foveal::vmtest
