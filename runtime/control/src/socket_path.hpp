#pragma once
// The rules for where the control socket may live (docs/daemon.md, "Control socket"): a
// private directory of this user, and nothing but a stale socket ever replaced.
#include <sys/un.h>

#include <string>

#include "foveal/core/error.hpp"

namespace foveal::control_detail {

Result<sockaddr_un> socket_address(const std::string& path);

/// Creates `dir` and its missing parents with mode 0700, or checks that an existing
/// `dir` is a directory (not a link) owned by this user with no group or other access.
/// Never changes an existing directory; a refusal names it and says what is wrong.
Status prepare_private_dir(const std::string& dir);

/// Leaves `path` free for bind(): absent, or a socket nobody listens on (removed).
/// A live socket, or anything that is not a socket, is refused and left alone.
Status clear_stale_socket(const std::string& path, const sockaddr_un& addr);

}  // namespace foveal::control_detail
