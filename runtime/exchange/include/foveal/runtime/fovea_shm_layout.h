/* The fovea block's layout (docs/fovea-shm.md), in C so that foveald (C++) and
 * foveal-client (C) share one definition. Plain data only: each side reads and writes
 * the words with its own atomics. Little-endian, naturally aligned.
 *
 * Rule for later versions: sections are appended at the end and never grow, move or
 * change meaning, so a reader of version N reads any block of version >= N whose size
 * is at least the size of version N. */
#ifndef FOVEAL_RUNTIME_FOVEA_SHM_LAYOUT_H
#define FOVEAL_RUNTIME_FOVEA_SHM_LAYOUT_H

#include <stdint.h>

#define FOVEAL_SHM_MAGIC 0x41564F46u /* "FOVA" little-endian */
#define FOVEAL_SHM_VERSION 4u /* 1: fovea only; 2: + settings, writer liveness; 3: + view; 4: + motion */

/* The fovea section's payload (unchanged since version 1). */
typedef struct foveal_shm_fovea {
  int64_t t_ns;          /* CLOCK_MONOTONIC of the gaze sample */
  uint32_t eye_width;    /* the viewport the pixels refer to */
  uint32_t eye_height;
  float x[2], y[2];      /* per eye (0 left, 1 right): viewport pixels, origin top-left, y down */
  float confidence[2];   /* 0..1 */
  uint32_t state[2];     /* 0 fixation, 1 saccade, 2 pursuit, 3 blink, 4 lost */
  uint64_t frame;        /* increments with every publish; 0: nothing published yet */
} foveal_shm_fovea;

/* The settings section's payload (version 2): the active profile's EFR pair and f. */
typedef struct foveal_shm_settings {
  double sigma_d, sigma_nd; /* RMFR levels of the dominant and the non-dominant eye */
  double f_x, f_y;          /* RMFR's f per axis; < 0: automatic */
  uint32_t dominant_eye;    /* 0 left, 1 right */
  uint32_t reserved;
  uint64_t generation;      /* increments with every change; 0: nothing published yet */
} foveal_shm_settings;

/* The view section's payload (version 3): what the fovea's pixels mean, so that a reader
 * can turn them back into gaze directions (docs/display-model.md). Written once, before
 * the first fovea; the display model is fixed while foveald runs. */
typedef struct foveal_shm_view {
  float tan_left[2], tan_right[2]; /* per eye: the frustum's half-angle tangents (left, bottom < 0) */
  float tan_bottom[2], tan_top[2];
  float ipd_m;                     /* interpupillary distance, metres */
  uint32_t published;              /* 1 once written; 0: not yet */
} foveal_shm_view;

/* The motion section's payload (version 4): what foveald's prediction to display time
 * needs beyond the fovea (runtime/fovea fovea_prediction.hpp): per eye the gaze
 * pipeline's velocity, the smoother's lag and whether the point may be extrapolated.
 * `frame` names the fovea it belongs to: foveald writes it just before that fovea, so a
 * reader that reads the fovea and then the motion pairs them only when the frames match. */
typedef struct foveal_shm_motion {
  float velocity_x[2], velocity_y[2]; /* viewport px/s, y down */
  float lag_x[2], lag_y[2];           /* px the point trails the gaze in a steady movement */
  uint32_t predictable[2];            /* 1: fixation or pursuit on the eye's own sample; 0: hold it */
  uint64_t frame;                     /* the fovea's frame; 0: nothing published yet */
} foveal_shm_motion;

/* Writer states (the word at FOVEAL_SHM_WRITER_STATE_OFFSET). */
#define FOVEAL_SHM_WRITER_LIVE 1u
#define FOVEAL_SHM_WRITER_STOPPED 2u /* foveald stopped and removed the block's name */

/* The writer refreshes the heartbeat at least this often; a reader that sees it older
 * than FOVEAL_SHM_DEAD_AFTER_NS takes the writer for dead (killed, crashed, hung). */
#define FOVEAL_SHM_HEARTBEAT_NS 10000000LL      /* 10 ms: foveald's control thread */
#define FOVEAL_SHM_DEAD_AFTER_NS 2000000000LL   /* 2 s */

/* Byte offsets. A seqlock section is a u32 sequence counter (odd while a write is in
 * progress), 4 bytes of padding, then the payload as 64-bit words. */
enum {
  FOVEAL_SHM_MAGIC_OFFSET = 0,          /* u32 */
  FOVEAL_SHM_VERSION_OFFSET = 4,        /* u32 */
  FOVEAL_SHM_SIZE_OFFSET = 8,           /* u32: the block's size in bytes */
  FOVEAL_SHM_FOVEA_SEQ_OFFSET = 16,     /* u32 */
  FOVEAL_SHM_FOVEA_WORDS_OFFSET = 24,   /* foveal_shm_fovea as 7 u64 */
  FOVEAL_SHM_V1_SIZE = 80,
  /* version 2 */
  FOVEAL_SHM_SETTINGS_SEQ_OFFSET = 80,   /* u32 */
  FOVEAL_SHM_SETTINGS_WORDS_OFFSET = 88, /* foveal_shm_settings as 6 u64 */
  FOVEAL_SHM_HEARTBEAT_OFFSET = 136,     /* i64: CLOCK_MONOTONIC of the writer's last sign of life */
  FOVEAL_SHM_WRITER_PID_OFFSET = 144,    /* u32: the writer's process id (for messages) */
  FOVEAL_SHM_WRITER_STATE_OFFSET = 148,  /* u32: FOVEAL_SHM_WRITER_* */
  FOVEAL_SHM_V2_SIZE = 152,
  /* version 3 */
  FOVEAL_SHM_VIEW_SEQ_OFFSET = 152,   /* u32 */
  FOVEAL_SHM_VIEW_WORDS_OFFSET = 160, /* foveal_shm_view as 5 u64 */
  FOVEAL_SHM_V3_SIZE = 200,
  /* version 4 */
  FOVEAL_SHM_MOTION_SEQ_OFFSET = 200,   /* u32 */
  FOVEAL_SHM_MOTION_WORDS_OFFSET = 208, /* foveal_shm_motion as 6 u64 */
  FOVEAL_SHM_V4_SIZE = 256
};

#define FOVEAL_SHM_FOVEA_WORDS ((sizeof(foveal_shm_fovea) + 7) / 8)
#define FOVEAL_SHM_SETTINGS_WORDS ((sizeof(foveal_shm_settings) + 7) / 8)
#define FOVEAL_SHM_VIEW_WORDS ((sizeof(foveal_shm_view) + 7) / 8)
#define FOVEAL_SHM_MOTION_WORDS ((sizeof(foveal_shm_motion) + 7) / 8)

#endif
