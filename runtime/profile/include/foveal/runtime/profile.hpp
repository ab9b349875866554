#pragma once
// Per-user settings: dominant eye, the EFR pair (sigma_d, sigma_nd), f_x/f_y, IPD,
// display model and filter overrides (docs/profiles.md).
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/error.hpp"
#include "foveal/core/gaze_sample.hpp"

namespace foveal {

/// The gaze data quality measured in calibration's validation trials (docs/profiles.md,
/// docs/calibration.md), in the measures of docs/quality.md. NaN: not measurable.
struct ProfileGazeQuality {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  struct Channel {
    double accuracy_deg = kNaN;     ///< mean offset from the targets
    double rms_s2s_deg = kNaN;      ///< precision, sample to sample
    double std_deg = kNaN;          ///< precision, spread
    double data_loss_pct = kNaN;
  };
  std::array<Channel, 3> channels;  ///< left, right, binocular
  int targets = 0;                  ///< fixation targets measured
  std::string source;               ///< where the gaze came from (log path or source spec)
};

/// RMFR's f (a fraction of the eye's width or height) where the compositor is tested:
/// docs/stability.md runs every method at f in {0.01, 0.05, 0.3, 1, 10}. Profiles and the
/// levels tables hold f inside it (f = 1e-300 was taken as it was).
inline constexpr double kMinRmfrF = 0.01, kMaxRmfrF = 10.0;

struct Profile {
  std::string name;
  Eye dominant_eye = Eye::right;   ///< ~70% of people are right-eye dominant
  double sigma_d = 2.0;            ///< dominant eye's foveation level (EFR seed: sigma_UF)
  double sigma_nd = 3.0;           ///< non-dominant eye's level (EFR seed: sigma_NF), >= sigma_d
  std::optional<double> f_x = 0.3; ///< fraction of W, [kMinRmfrF, kMaxRmfrF]; nullopt = "auto"
  std::optional<double> f_y = 0.3; ///< fraction of H; nullopt = "auto"
  double ipd_mm = 63.0;
  std::string display_model = "htc_vive_pro_eye";  ///< a name in data/display or a path
  nlohmann::json filter = nlohmann::json::object(); ///< FilterConfig overrides (validated)
  std::optional<ProfileGazeQuality> gaze_quality;   ///< from the last calibration with gaze
  /// Levels chosen by perception: "jod:T" picks sigma_d, sigma_nd and f from the display
  /// model's JOD table (foveal/runtime/jod_levels.hpp); empty: the levels above.
  std::string quality;
  /// Foveated temporal accumulation (docs/rmfr.md, "Temporal accumulation"): "on" or "off"
  /// (the default; written to the file only when on).
  bool temporal = false;

  /// sigma for an eye: sigma_d for the dominant one, sigma_nd for the other.
  double sigma(Eye e) const { return e == dominant_eye ? sigma_d : sigma_nd; }

  nlohmann::json to_json() const;
  /// Strict: unknown keys, wrong types and out-of-range values are errors naming
  /// `where` and the key. Missing keys take the defaults above.
  static Result<Profile> from_json(const nlohmann::json& j, const std::string& name, const std::string& where);
  /// Checks ranges: 1 <= sigma_d <= sigma_nd <= 16, 0 < f <= 100, 40 < ipd < 90 mm.
  Status validate(const std::string& where) const;
  /// Sets one key from text ("dominant_eye" "left", "sigma_d" "2.2", "f_x" "auto"...).
  Status set(const std::string& key, const std::string& value);
};

/// A quality setting: "" or "off" -> no target; "jod:T" -> T, in (0, 10]. Errors start
/// with `where`.
Result<std::optional<double>> parse_quality(const std::string& spec, const std::string& where);

/// True for names made of letters, digits, '-' and '_', 1..64 characters.
bool valid_profile_name(const std::string& name);

/// Profiles on disk: <config>/foveal/profiles/NAME.json, the active one's name in
/// <config>/foveal/active; <config> is $XDG_CONFIG_HOME or ~/.config. Every write is
/// atomic; a read-modify-write (profile set, create, import, calibrate) holds lock()
/// so that concurrent writers take turns instead of losing updates.
class ProfileStore {
 public:
  /// The store under the user's config directory.
  static ProfileStore user();
  explicit ProfileStore(std::string root) : root_(std::move(root)) {}

  const std::string& root() const { return root_; }
  std::string path_of(const std::string& name) const { return root_ + "/profiles/" + name + ".json"; }

  Result<std::vector<std::string>> list() const;
  Result<Profile> load(const std::string& name) const;
  /// Loads a profile file from anywhere (import, daemon reload).
  static Result<Profile> load_file(const std::string& path, const std::string& name);
  Status save(const Profile& p) const;
  Status remove(const std::string& name) const;
  bool exists(const std::string& name) const;

  /// The active profile's name: the one `use` chose, else "default". An error names
  /// the file when it is there but not a readable regular file (a FIFO, a device).
  Result<std::string> active() const;
  Status set_active(const std::string& name) const;

  /// An exclusive flock on <root>/lock, released when destroyed (or when the process
  /// dies). Readers need none: every file is replaced atomically.
  class Lock {
   public:
    explicit Lock(int fd) : fd_(fd) {}
    Lock(Lock&& o) noexcept : fd_(o.fd_) { o.fd_ = -1; }
    Lock& operator=(Lock&&) = delete;
    ~Lock();

   private:
    int fd_;
  };
  /// Waits up to `timeout_ms` for the lock; an io error naming the lock file after that.
  Result<Lock> lock(int timeout_ms = 10000) const;

 private:
  std::string root_;
};

}  // namespace foveal
