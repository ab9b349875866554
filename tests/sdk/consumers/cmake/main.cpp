// The C++ side of the SDK install test: the same header from C++, through
// find_package(foveal CONFIG). Same protocol as consumer.c.
#include <foveal/client.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <thread>

namespace {

bool inside(float v, std::uint32_t size) { return std::isfinite(v) && v >= 0.0f && v <= static_cast<float>(size); }
void sleep_ms(int ms) { std::this_thread::sleep_for(std::chrono::milliseconds(ms)); }

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return std::fprintf(stderr, "usage: consumer_cpp SIGMA_D\n"), 2;
  const double want = std::atof(argv[1]);
  foveal_error err{};
  foveal_client* c = nullptr;
  for (int i = 0; i < 600 && !c; ++i)  // hang guards of 60 s at least
    if (!(c = foveal_client_open(nullptr, &err))) sleep_ms(100);
  if (!c) return std::fprintf(stderr, "consumer_cpp: %s\n", err.message), 1;
  foveal_fovea f{};
  int rc = FOVEAL_ERR_NO_DATA;
  for (int i = 0; i < 600 && rc == FOVEAL_ERR_NO_DATA; ++i)
    if ((rc = foveal_client_read(c, &f)) == FOVEAL_ERR_NO_DATA) sleep_ms(100);
  if (rc != FOVEAL_OK) return std::fprintf(stderr, "consumer_cpp: read: %s\n", foveal_error_message(rc)), 1;
  for (int e = 0; e < 2; ++e)
    if (!inside(f.x[e], f.eye_width) || !inside(f.y[e], f.eye_height) || !std::isfinite(f.confidence[e]))
      return std::fprintf(stderr, "consumer_cpp: eye %d at (%f, %f) is outside %ux%u\n", e, f.x[e], f.y[e],
                          f.eye_width, f.eye_height),
             1;
  std::printf("fovea ok frame=%llu left=(%.1f,%.1f) right=(%.1f,%.1f) viewport=%ux%u\n",
              static_cast<unsigned long long>(f.frame), f.x[0], f.y[0], f.x[1], f.y[1], f.eye_width, f.eye_height);
  foveal_settings s{};
  if ((rc = foveal_client_settings(c, &s)) != FOVEAL_OK)
    return std::fprintf(stderr, "consumer_cpp: settings: %s\n", foveal_error_message(rc)), 1;
  const std::uint64_t first = s.generation;
  std::printf("ready generation=%llu sigma_d=%g\n", static_cast<unsigned long long>(first), s.sigma_d);
  std::fflush(stdout);
  for (int i = 0; i < 6000; ++i, sleep_ms(10)) {
    if ((rc = foveal_client_settings(c, &s)) != FOVEAL_OK)
      return std::fprintf(stderr, "consumer_cpp: settings: %s\n", foveal_error_message(rc)), 1;
    if (s.generation > first && s.sigma_d == want) {
      std::printf("settings changed generation=%llu sigma_d=%g sigma_nd=%g dominant=%d\n",
                  static_cast<unsigned long long>(s.generation), s.sigma_d, s.sigma_nd, s.dominant_eye);
      foveal_client_close(c);
      return 0;
    }
  }
  std::fprintf(stderr, "consumer_cpp: sigma_d stayed %g, expected %g\n", s.sigma_d, want);
  return 1;
}
