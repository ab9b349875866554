/* An outside program on foveal-client (the SDK install test builds it against an
 * installed prefix): reads the live fovea, checks it, then waits for a settings change.
 *   consumer SIGMA_D   prints "fovea ok ..." and "ready generation=G", then exits 0 once
 *                      the block's sigma_d equals SIGMA_D with a later generation;
 *                      exit 1 with a message on any error or after 20 s. */
#define _POSIX_C_SOURCE 200809L
#include <foveal/client.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static void sleep_ms(long ms) {
  struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
  nanosleep(&ts, NULL);
}

static int inside(float v, uint32_t size) { return isfinite(v) && v >= 0.0f && v <= (float)size; }

int main(int argc, char **argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: consumer SIGMA_D\n");
    return 2;
  }
  const double want = atof(argv[1]);
  foveal_error err;
  foveal_client *c = NULL;
  for (int i = 0; i < 600 && !c; ++i) { /* foveald may still be starting */
    c = foveal_client_open(NULL, &err);
    if (!c) sleep_ms(100);
  }
  if (!c) {
    fprintf(stderr, "consumer: %s\n", err.message);
    return 1;
  }
  foveal_fovea f;
  int rc = FOVEAL_ERR_NO_DATA;
  for (int i = 0; i < 600 && rc == FOVEAL_ERR_NO_DATA; ++i) {
    rc = foveal_client_read(c, &f);
    if (rc == FOVEAL_ERR_NO_DATA) sleep_ms(100);
  }
  if (rc != FOVEAL_OK) {
    fprintf(stderr, "consumer: read: %s\n", foveal_error_message(rc));
    return 1;
  }
  for (int e = 0; e < 2; ++e)
    if (!inside(f.x[e], f.eye_width) || !inside(f.y[e], f.eye_height) || !isfinite(f.confidence[e])) {
      fprintf(stderr, "consumer: eye %d at (%f, %f) is outside %ux%u\n", e, f.x[e], f.y[e], f.eye_width, f.eye_height);
      return 1;
    }
  printf("fovea ok frame=%llu left=(%.1f,%.1f) right=(%.1f,%.1f) viewport=%ux%u\n", (unsigned long long)f.frame,
         f.x[0], f.y[0], f.x[1], f.y[1], f.eye_width, f.eye_height);
  foveal_settings s;
  if ((rc = foveal_client_settings(c, &s)) != FOVEAL_OK) {
    fprintf(stderr, "consumer: settings: %s\n", foveal_error_message(rc));
    return 1;
  }
  const uint64_t first = s.generation;
  printf("ready generation=%llu sigma_d=%g\n", (unsigned long long)first, s.sigma_d);
  fflush(stdout);
  for (int i = 0; i < 6000; ++i) { /* 60 s at least: a hang guard */
    if ((rc = foveal_client_settings(c, &s)) != FOVEAL_OK) {
      fprintf(stderr, "consumer: settings: %s\n", foveal_error_message(rc));
      return 1;
    }
    if (s.generation > first && s.sigma_d == want) {
      printf("settings changed generation=%llu sigma_d=%g sigma_nd=%g dominant=%d\n", (unsigned long long)s.generation,
             s.sigma_d, s.sigma_nd, s.dominant_eye);
      foveal_client_close(c);
      return 0;
    }
    sleep_ms(10);
  }
  fprintf(stderr, "consumer: sigma_d stayed %g (generation %llu), expected %g\n", s.sigma_d,
          (unsigned long long)s.generation, want);
  return 1;
}
