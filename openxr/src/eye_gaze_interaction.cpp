// XR_EXT_eye_gaze_interaction through the action system: the layer takes the eye-gaze
// profile's bindings out of the app's suggestions, answers the action state of the
// actions bound there and locates their action spaces from the runtime's head pose and
// foveald's gaze. Everything else goes to the runtime unchanged. docs/openxr.md.
#include <cstring>
#include <type_traits>
#include <vector>

#include "eye_gaze_system.hpp"
#include "layer.hpp"
#include "pose_math.hpp"

namespace foveal::openxr {

void LatchedGaze::store(bool active, const GazeNow& g) {
  static_assert(std::is_trivially_copyable_v<GazeNow>);
  std::array<std::uint64_t, kWords> w{};
  std::memcpy(w.data(), &g, sizeof g);
  const std::uint32_t s = seq_.load(std::memory_order_relaxed);
  seq_.store(s + 1, std::memory_order_relaxed);
  std::atomic_thread_fence(std::memory_order_release);
  for (std::size_t i = 0; i < kWords; ++i) words_[i].store(w[i], std::memory_order_relaxed);
  active_.store(active, std::memory_order_relaxed);
  seq_.store(s + 2, std::memory_order_release);
}

bool LatchedGaze::load(GazeNow& g) const {
  for (;;) {
    const std::uint32_t before = seq_.load(std::memory_order_acquire);
    if (before & 1) continue;  // a store is under way on another thread: a few instructions
    const bool active = active_.load(std::memory_order_relaxed);
    std::array<std::uint64_t, kWords> w;
    for (std::size_t i = 0; i < kWords; ++i) w[i] = words_[i].load(std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_acquire);
    if (seq_.load(std::memory_order_relaxed) != before) continue;
    std::memcpy(static_cast<void*>(&g), w.data(), sizeof g);
    return active;
  }
}

namespace {

bool serving() { return layer().serve_ext.load(std::memory_order_relaxed); }

/// The runtime does not know /user/eyes_ext when it lacks the extension: the layer
/// keeps that subaction path to itself.
bool hide_eyes(XrPath p) {
  return !layer().runtime_has(Ext::eye_gaze_interaction) && p == layer().eyes_path && p != XR_NULL_PATH;
}

/// `set` is attached to a session. Under the layer's mutex.
bool set_attached(XrActionSet set) { return find_slot(layer().attached_sets, set) != nullptr; }

bool is_gaze_action(XrAction a, ActionSlot** slot = nullptr) {
  if (!serving()) return false;
  ActionSlot* s = find_action(a);
  if (slot) *slot = s;
  return s && s->gaze.load(std::memory_order_acquire);
}

/// The gaze pose in the head frame for one read of foveald's sample.
XrPosef gaze_in_head(const GazeNow& g) { return {look_rotation(g.combined), {0, 0, 0}}; }

}  // namespace

XrResult locate_head(const SessionSlot& s, XrSpace base, XrTime time, XrSpaceLocation& head) {
  head = {XR_TYPE_SPACE_LOCATION, nullptr, 0, identity_pose()};
  return layer().next.LocateSpace(s.view, base, time, &head);
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrCreateAction(XrActionSet set, const XrActionCreateInfo* info, XrAction* action) {
  Layer& l = layer();
  if (!info) return l.next.CreateAction(set, info, action);
  XrActionCreateInfo down = *info;
  std::vector<XrPath> paths;
  for (std::uint32_t i = 0; i < info->countSubactionPaths; ++i)
    if (!hide_eyes(info->subactionPaths[i])) paths.push_back(info->subactionPaths[i]);
  down.countSubactionPaths = static_cast<std::uint32_t>(paths.size());
  down.subactionPaths = paths.empty() ? nullptr : paths.data();
  const XrResult r = l.next.CreateAction(set, &down, action);
  if (XR_FAILED(r) || info->actionType != XR_ACTION_TYPE_POSE_INPUT) return r;
  std::lock_guard lock(l.mutex);
  const bool claimed = claim_slot(l.actions, *action, [set](ActionSlot& slot) {
    slot.set = set;
    slot.gaze = false;
    slot.set_active = false;
  });
  if (!claimed) log_line("more than 64 pose actions: the later ones cannot be bound to eye gaze");
  return r;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrDestroyAction(XrAction action) {
  Layer& l = layer();
  {
    std::lock_guard lock(l.mutex);
    if (ActionSlot* s = find_action(action)) s->handle.store(XR_NULL_HANDLE);
  }
  return l.next.DestroyAction(action);
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrDestroyActionSet(XrActionSet set) {
  Layer& l = layer();
  {
    std::lock_guard lock(l.mutex);
    for (auto& s : l.actions)
      if (s.handle.load() != XR_NULL_HANDLE && s.set == set) s.handle.store(XR_NULL_HANDLE);
  }
  return l.next.DestroyActionSet(set);
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrSuggestInteractionProfileBindings(
    XrInstance instance, const XrInteractionProfileSuggestedBinding* suggested) {
  Layer& l = layer();
  if (!serving() || !suggested || suggested->interactionProfile != l.profile_path)
    return l.next.SuggestInteractionProfileBindings(instance, suggested);
  // The eye-gaze profile is the layer's: the runtime never sees these bindings.
  std::lock_guard lock(l.mutex);
  if (suggested->countSuggestedBindings == 0 || !suggested->suggestedBindings) return XR_ERROR_VALIDATION_FAILURE;
  for (std::uint32_t i = 0; i < suggested->countSuggestedBindings; ++i) {
    const XrActionSuggestedBinding& b = suggested->suggestedBindings[i];
    if (b.binding != l.gaze_pose_path && b.binding != l.gaze_path) return XR_ERROR_PATH_UNSUPPORTED;
    const ActionSlot* a = find_action(b.action);
    if (!a) return XR_ERROR_HANDLE_INVALID;  // or not a pose action
    // Refused only for an action whose own set is attached (a new set for a second
    // session binds as the first one did): the specification's rule and Monado's.
    if (set_attached(a->set)) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
  }
  // A new suggestion for a profile replaces the previous one (the specification's rule).
  for (auto& s : l.actions) s.gaze = false;
  for (std::uint32_t i = 0; i < suggested->countSuggestedBindings; ++i)
    find_action(suggested->suggestedBindings[i].action)->gaze.store(true, std::memory_order_release);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrAttachSessionActionSets(XrSession session,
                                                               const XrSessionActionSetsAttachInfo* info) {
  Layer& l = layer();
  const XrResult r = l.next.AttachSessionActionSets(session, info);
  if (XR_SUCCEEDED(r) && info && info->actionSets) {
    std::lock_guard lock(l.mutex);
    for (std::uint32_t i = 0; i < info->countActionSets; ++i) {
      if (set_attached(info->actionSets[i])) continue;
      if (!claim_slot(l.attached_sets, info->actionSets[i], [session](AttachedSetSlot& s) { s.session = session; }))
        log_line("more than 64 attached action sets: the later ones may take new eye-gaze bindings");
    }
  }
  return r;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrGetCurrentInteractionProfile(XrSession session, XrPath top_level,
                                                                    XrInteractionProfileState* state) {
  Layer& l = layer();
  if (!serving() || top_level != l.eyes_path || !state)
    return l.next.GetCurrentInteractionProfile(session, top_level, state);
  // The profile is current for a session with an attached set that holds a gaze action.
  bool bound = false;
  for (auto& s : l.actions) {
    if (s.handle.load(std::memory_order_acquire) == XR_NULL_HANDLE || !s.gaze.load()) continue;
    for (auto& a : l.attached_sets)
      bound |= a.handle.load(std::memory_order_acquire) == s.set && a.session == session;
  }
  state->interactionProfile = bound ? l.profile_path : XR_NULL_PATH;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrSyncActions(XrSession session, const XrActionsSyncInfo* info) {
  Layer& l = layer();
  if (!serving() || !info) return l.next.SyncActions(session, info);
  // The runtime cannot take /user/eyes_ext as a subaction path it does not know: a copy
  // without it, on the stack (this runs every frame).
  constexpr std::uint32_t kMaxSets = 32;
  XrActiveActionSet sets[kMaxSets];
  const XrActionsSyncInfo* down = info;
  XrActionsSyncInfo copy = *info;
  if (info->countActiveActionSets <= kMaxSets && info->activeActionSets) {
    for (std::uint32_t i = 0; i < info->countActiveActionSets; ++i) {
      sets[i] = info->activeActionSets[i];
      if (hide_eyes(sets[i].subactionPath)) sets[i].subactionPath = XR_NULL_PATH;
    }
    copy.activeActionSets = sets;
    down = &copy;
  }
  const XrResult r = l.next.SyncActions(session, down);
  if (XR_FAILED(r)) return r;
  // The action state is what it was at the sync: latched here.
  SessionSlot* s = find_session(session);
  GazeNow g;
  const bool active = s && s->focused.load() && l.feed && l.feed->read(g) && g.tracked;
  if (s) {
    s->latched.store(active, g);
    s->gaze_active.store(active, std::memory_order_release);
  }
  bool reads_gaze = false;
  for (auto& a : l.actions) {
    if (a.handle.load(std::memory_order_acquire) == XR_NULL_HANDLE || !a.gaze.load()) continue;
    bool set_active = false;
    for (std::uint32_t i = 0; i < info->countActiveActionSets && info->activeActionSets; ++i)
      set_active |= info->activeActionSets[i].actionSet == a.set;
    a.set_active.store(set_active, std::memory_order_release);
    reads_gaze |= set_active;
  }
  if (s) s->app_reads_gaze.store(reads_gaze, std::memory_order_release);
  return r;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrGetActionStatePose(XrSession session, const XrActionStateGetInfo* info,
                                                          XrActionStatePose* state) {
  Layer& l = layer();
  ActionSlot* a = nullptr;
  if (!info || !state || !is_gaze_action(info->action, &a)) {
    if (info && hide_eyes(info->subactionPath)) {
      XrActionStateGetInfo down = *info;
      down.subactionPath = XR_NULL_PATH;
      return l.next.GetActionStatePose(session, &down, state);
    }
    return l.next.GetActionStatePose(session, info, state);
  }
  if (info->subactionPath != XR_NULL_PATH && info->subactionPath != l.eyes_path) return XR_ERROR_PATH_UNSUPPORTED;
  const SessionSlot* s = find_session(session);
  state->isActive = s && s->gaze_active.load(std::memory_order_acquire) && a->set_active.load() ? XR_TRUE : XR_FALSE;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrCreateActionSpace(XrSession session, const XrActionSpaceCreateInfo* info,
                                                         XrSpace* space) {
  Layer& l = layer();
  if (!info || !space) return l.next.CreateActionSpace(session, info, space);
  XrActionSpaceCreateInfo down = *info;
  if (hide_eyes(down.subactionPath)) down.subactionPath = XR_NULL_PATH;
  const XrResult r = l.next.CreateActionSpace(session, &down, space);
  if (XR_FAILED(r)) return r;
  // Every pose action's space is noted: its binding to eye gaze may be suggested later.
  std::lock_guard lock(l.mutex);
  ActionSlot* a = find_action(info->action);
  if (!a) return r;
  const int index = static_cast<int>(a - l.actions.data());
  const bool claimed = claim_slot(l.spaces, *space, [&](SpaceSlot& slot) {
    slot.action = index;
    slot.session = session;
    slot.pose_in_action = info->poseInActionSpace;
  });
  if (!claimed) log_line("more than 64 pose action spaces: the later ones show no eye gaze");
  return r;
}

namespace {

/// A gaze action space's pose in the head frame at `time`, or false when the gaze is not
/// there (not bound, not active, no sample): the sample latched at the last sync,
/// predicted to `time` (gaze_at). g keeps the sample's time.
bool gaze_space_in_head(const SpaceSlot& sp, XrTime time, GazeNow& g, XrPosef& pose, const SessionSlot*& session) {
  Layer& l = layer();
  const ActionSlot& a = l.actions[static_cast<std::size_t>(sp.action)];
  session = find_session(sp.session);
  if (!session || !session->gaze_active.load(std::memory_order_acquire) || !a.set_active.load()) return false;
  if (!session->latched.load(g)) return false;
  g = gaze_at(g, time);
  pose = compose(gaze_in_head(g), sp.pose_in_action);
  return true;
}

/// The structs an app may chain to a gaze space's location: the sample's time (when the
/// sample the pose comes from was taken, also when the pose is predicted from it to the
/// locate's time, as the extension says) and no velocity.
void fill_chain(XrSpaceLocation* location, const GazeNow* g) {
  for (auto* p = reinterpret_cast<XrBaseOutStructure*>(location->next); p; p = p->next) {
    if (p->type == XR_TYPE_EYE_GAZE_SAMPLE_TIME_EXT)
      reinterpret_cast<XrEyeGazeSampleTimeEXT*>(p)->time = g ? layer().feed->to_xr_time(g->t_ns) : 0;
    if (p->type == XR_TYPE_SPACE_VELOCITY) reinterpret_cast<XrSpaceVelocity*>(p)->velocityFlags = 0;
  }
}

}  // namespace

bool is_gaze_action_space(const SpaceSlot* s) {
  return serving() && s && s->action >= 0 &&
         layer().actions[static_cast<std::size_t>(s->action)].gaze.load(std::memory_order_acquire);
}

XrResult locate_gaze_action_space(XrSpace space, XrSpace base, XrTime time, XrSpaceLocation* location,
                                  const SpaceSlot* sp, const SpaceSlot* bp) {
  const bool space_gaze = is_gaze_action_space(sp), base_gaze = is_gaze_action_space(bp);

  // The runtime must not see the extension's struct it may not know: it is filled here.
  void* chain = location->next;
  location->locationFlags = 0;
  location->pose = identity_pose();
  GazeNow g;
  XrPosef gaze{};
  const SessionSlot* session = nullptr;
  const XrSpaceLocationFlags kOrientation = XR_SPACE_LOCATION_ORIENTATION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT;
  if (space_gaze && base_gaze) {
    GazeNow g2;
    XrPosef gaze_base{};
    const SessionSlot* s2 = nullptr;
    if (gaze_space_in_head(*sp, time, g, gaze, session) && gaze_space_in_head(*bp, time, g2, gaze_base, s2)) {
      location->pose = compose(inverse(gaze_base), gaze);
      location->locationFlags = kOrientation | XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_POSITION_TRACKED_BIT;
      fill_chain(location, &g);
    } else {
      fill_chain(location, nullptr);
    }
    return XR_SUCCESS;
  }
  const SpaceSlot& gaze_slot = space_gaze ? *sp : *bp;
  fill_chain(location, nullptr);
  if (!gaze_space_in_head(gaze_slot, time, g, gaze, session)) return XR_SUCCESS;  // inactive: no flags
  XrSpaceLocation head{};
  location->next = nullptr;
  const XrResult r = space_gaze ? locate_head(*session, base, time, head)
                                : locate_head(*session, space, time, head);  // head in the other space
  location->next = chain;
  if (XR_FAILED(r)) return r;
  if (!(head.locationFlags & XR_SPACE_LOCATION_ORIENTATION_VALID_BIT)) return XR_SUCCESS;
  // space_gaze: gaze in base = head-in-base ∘ gaze-in-head; else space in gaze = (head-in-space ∘ gaze)^-1.
  const XrPosef gaze_in_other = compose(head.pose, gaze);
  location->pose = space_gaze ? gaze_in_other : inverse(gaze_in_other);
  location->locationFlags =
      (head.locationFlags & (XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_POSITION_TRACKED_BIT)) |
      XR_SPACE_LOCATION_ORIENTATION_VALID_BIT |
      (head.locationFlags & XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT ? XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT : 0);
  fill_chain(location, &g);
  return XR_SUCCESS;
}

void fill_eye_gaze_properties(XrBaseOutStructure* p) {
  if (serving()) reinterpret_cast<XrSystemEyeGazeInteractionPropertiesEXT*>(p)->supportsEyeGazeInteraction = XR_TRUE;
}

namespace {
const Intercept kFunctions[] = {
    {"xrCreateAction", FOVEAL_FN(layer_xrCreateAction), false},
    {"xrDestroyAction", FOVEAL_FN(layer_xrDestroyAction), false},
    {"xrDestroyActionSet", FOVEAL_FN(layer_xrDestroyActionSet), false},
    {"xrSuggestInteractionProfileBindings", FOVEAL_FN(layer_xrSuggestInteractionProfileBindings), false},
    {"xrAttachSessionActionSets", FOVEAL_FN(layer_xrAttachSessionActionSets), false},
    {"xrGetCurrentInteractionProfile", FOVEAL_FN(layer_xrGetCurrentInteractionProfile), false},
    {"xrSyncActions", FOVEAL_FN(layer_xrSyncActions), false},
    {"xrGetActionStatePose", FOVEAL_FN(layer_xrGetActionStatePose), false},
    {"xrCreateActionSpace", FOVEAL_FN(layer_xrCreateActionSpace), false},
};
}  // namespace

const ServedExtension kEyeGazeInteraction = {
    XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME, 1, kFunctions, std::size(kFunctions),
    XR_TYPE_SYSTEM_EYE_GAZE_INTERACTION_PROPERTIES_EXT, fill_eye_gaze_properties, -1};

}  // namespace foveal::openxr
