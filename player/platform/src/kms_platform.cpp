// The board platform: EGL on a GBM surface, shown through DRM/KMS without a display server, as
// kmscube and mpv's drm output do it. One connector and CRTC, the primary plane; atomic modesetting
// where the driver offers it, legacy SetCrtc/PageFlip otherwise. Frames are paced by the page-flip
// events; hotplug arrives as kernel uevents; losing DRM master (a VT switch, another client) stops
// the commits until master comes back.
#include "backends.h"
#include "egl_util.h"
#include "kms_output.h"
#include "uevent.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <drm_fourcc.h>
#include <fcntl.h>
#include <gbm.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace platform {
namespace {

using SteadyClock = std::chrono::steady_clock;
using kms::Connector;
using kms::ConnectorState;

class Fd {
 public:
  Fd() = default;
  explicit Fd(int fd) : fd_(fd) {}
  Fd(Fd&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  Fd& operator=(Fd&& other) noexcept {
    reset(std::exchange(other.fd_, -1));
    return *this;
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() { reset(); }
  void reset(int fd = -1) {
    if (fd_ >= 0) close(fd_);
    fd_ = fd;
  }
  int get() const { return fd_; }
  explicit operator bool() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
};

template <class T, void (*Free)(T*)>
struct Deleter {
  void operator()(T* p) const {
    if (p != nullptr) Free(p);
  }
};
using ResourcesPtr = std::unique_ptr<drmModeRes, Deleter<drmModeRes, drmModeFreeResources>>;
using ConnectorPtr = std::unique_ptr<drmModeConnector, Deleter<drmModeConnector, drmModeFreeConnector>>;
using EncoderPtr = std::unique_ptr<drmModeEncoder, Deleter<drmModeEncoder, drmModeFreeEncoder>>;
using PlaneResourcesPtr = std::unique_ptr<drmModePlaneRes, Deleter<drmModePlaneRes, drmModeFreePlaneResources>>;
using PlanePtr = std::unique_ptr<drmModePlane, Deleter<drmModePlane, drmModeFreePlane>>;
using PropertiesPtr = std::unique_ptr<drmModeObjectProperties, Deleter<drmModeObjectProperties, drmModeFreeObjectProperties>>;
using PropertyPtr = std::unique_ptr<drmModePropertyRes, Deleter<drmModePropertyRes, drmModeFreeProperty>>;
using AtomicPtr = std::unique_ptr<drmModeAtomicReq, Deleter<drmModeAtomicReq, drmModeAtomicFree>>;

std::string errno_text(int code) { return std::strerror(code); }

std::string connector_name(const drmModeConnector& connector) {
  const char* type = drmModeGetConnectorTypeName(connector.connector_type);
  return std::string(type != nullptr ? type : "Unknown") + "-" + std::to_string(connector.connector_type_id);
}

kms::Mode to_mode(const drmModeModeInfo& info) {
  kms::Mode mode;
  mode.width = info.hdisplay;
  mode.height = info.vdisplay;
  const double totals = static_cast<double>(info.htotal) * static_cast<double>(info.vtotal);
  mode.refresh_hz = totals > 0.0 ? static_cast<double>(info.clock) * 1000.0 / totals : static_cast<double>(info.vrefresh);
  mode.interlaced = (info.flags & DRM_MODE_FLAG_INTERLACE) != 0;
  if (mode.interlaced) mode.refresh_hz *= 2.0;
  mode.preferred = (info.type & DRM_MODE_TYPE_PREFERRED) != 0;
  return mode;
}

// What the device's connectors say now (a full probe: the kernel asks the display), with the raw
// modes the kernel needs back, and the writeback connector where the driver has one.
struct Probe {
  std::vector<Connector> connectors;
  std::vector<std::vector<drmModeModeInfo>> raw_modes;
  std::uint32_t writeback = 0;
};

bool probe(int fd, Probe& out, std::string& error) {
  out = {};
  ResourcesPtr resources(drmModeGetResources(fd));
  if (!resources) {
    error = "drmModeGetResources failed (" + errno_text(errno) + "): not a KMS device";
    return false;
  }
  for (int i = 0; i < resources->count_connectors; ++i) {
    ConnectorPtr raw(drmModeGetConnector(fd, resources->connectors[i]));
    if (!raw) continue;
    if (raw->connector_type == DRM_MODE_CONNECTOR_WRITEBACK) {
      out.writeback = raw->connector_id;
      continue;
    }
    Connector connector;
    connector.id = raw->connector_id;
    connector.name = connector_name(*raw);
    connector.state = raw->connection == DRM_MODE_CONNECTED      ? ConnectorState::connected
                      : raw->connection == DRM_MODE_DISCONNECTED ? ConnectorState::disconnected
                                                                 : ConnectorState::unknown;
    std::vector<drmModeModeInfo> raw_modes(raw->modes, raw->modes + raw->count_modes);
    for (const drmModeModeInfo& info : raw_modes) connector.modes.push_back(to_mode(info));
    out.connectors.push_back(std::move(connector));
    out.raw_modes.push_back(std::move(raw_modes));
  }
  return true;
}

std::uint32_t property_id(int fd, std::uint32_t object, std::uint32_t type, const char* name) {
  PropertiesPtr properties(drmModeObjectGetProperties(fd, object, type));
  if (!properties) return 0;
  for (std::uint32_t i = 0; i < properties->count_props; ++i) {
    PropertyPtr property(drmModeGetProperty(fd, properties->props[i]));
    if (property && std::strcmp(property->name, name) == 0) return property->prop_id;
  }
  return 0;
}

std::uint64_t property_value(int fd, std::uint32_t object, std::uint32_t type, const char* name, std::uint64_t fallback) {
  PropertiesPtr properties(drmModeObjectGetProperties(fd, object, type));
  if (!properties) return fallback;
  for (std::uint32_t i = 0; i < properties->count_props; ++i) {
    PropertyPtr property(drmModeGetProperty(fd, properties->props[i]));
    if (property && std::strcmp(property->name, name) == 0) return properties->prop_values[i];
  }
  return fallback;
}

// The CRTC for a connector: the one it drives now, else the first its encoders can reach.
bool find_crtc(int fd, std::uint32_t connector_id, std::uint32_t& crtc, int& crtc_index) {
  ResourcesPtr resources(drmModeGetResources(fd));
  // Current state only: the connector was just probed, and a probe reads the display's EDID again.
  ConnectorPtr connector(drmModeGetConnectorCurrent(fd, connector_id));
  if (!resources || !connector) return false;
  auto index_of = [&](std::uint32_t id) {
    for (int i = 0; i < resources->count_crtcs; ++i)
      if (resources->crtcs[i] == id) return i;
    return -1;
  };
  if (connector->encoder_id != 0) {
    EncoderPtr encoder(drmModeGetEncoder(fd, connector->encoder_id));
    if (encoder && encoder->crtc_id != 0 && index_of(encoder->crtc_id) >= 0) {
      crtc = encoder->crtc_id;
      crtc_index = index_of(crtc);
      return true;
    }
  }
  for (int e = 0; e < connector->count_encoders; ++e) {
    EncoderPtr encoder(drmModeGetEncoder(fd, connector->encoders[e]));
    if (!encoder) continue;
    for (int i = 0; i < resources->count_crtcs; ++i)
      if ((encoder->possible_crtcs & (1u << i)) != 0) {
        crtc = resources->crtcs[i];
        crtc_index = i;
        return true;
      }
  }
  return false;
}

std::uint32_t find_primary_plane(int fd, int crtc_index) {
  PlaneResourcesPtr planes(drmModeGetPlaneResources(fd));
  if (!planes) return 0;
  for (std::uint32_t i = 0; i < planes->count_planes; ++i) {
    PlanePtr plane(drmModeGetPlane(fd, planes->planes[i]));
    if (!plane || (plane->possible_crtcs & (1u << crtc_index)) == 0) continue;
    if (property_value(fd, plane->plane_id, DRM_MODE_OBJECT_PLANE, "type", UINT64_MAX) == DRM_PLANE_TYPE_PRIMARY)
      return plane->plane_id;
  }
  return 0;
}

bool has_kms(int fd) {
  ResourcesPtr resources(drmModeGetResources(fd));
  return resources && resources->count_connectors > 0 && resources->count_crtcs > 0;
}

bool has_connected_display(int fd) {
  Probe found;
  std::string ignored;
  if (!probe(fd, found, ignored)) return false;
  bool waiting = false;
  return kms::choose_connector(found.connectors, "auto", waiting, ignored) >= 0;
}

// Primary nodes of every DRM device, in the kernel's order.
std::vector<std::string> primary_nodes() {
  std::vector<std::string> nodes;
  drmDevicePtr devices[16];
  const int count = drmGetDevices2(0, devices, 16);
  if (count <= 0) return nodes;
  for (int i = 0; i < count; ++i)
    if ((devices[i]->available_nodes & (1 << DRM_NODE_PRIMARY)) != 0) nodes.emplace_back(devices[i]->nodes[DRM_NODE_PRIMARY]);
  drmFreeDevices(devices, count);
  return nodes;
}

Fd open_node(const std::string& path) { return Fd(open(path.c_str(), O_RDWR | O_CLOEXEC)); }

// The device to drive: the one named, else the first with KMS and a connected display, else the
// first with KMS (a display may be plugged in later). Card numbers change between boots, so the
// choice is by capability.
bool open_device(const std::string& wanted, Fd& fd, std::string& path, std::string& error) {
  if (!wanted.empty()) {
    fd = open_node(wanted);
    if (!fd) {
      error = "--drm-device: cannot open " + wanted + " (" + errno_text(errno) + ")";
      return false;
    }
    if (!has_kms(fd.get())) {
      error = "--drm-device: " + wanted + " has no KMS connectors and CRTCs (a render-only GPU?)";
      return false;
    }
    char resolved[PATH_MAX];
    path = realpath(wanted.c_str(), resolved) != nullptr ? resolved : wanted;
    return true;
  }
  const std::vector<std::string> nodes = primary_nodes();
  std::string fallback, tried;
  for (const std::string& node : nodes) {
    Fd candidate = open_node(node);
    if (!candidate) {
      tried += " " + node + " (" + errno_text(errno) + ")";
      continue;
    }
    if (!has_kms(candidate.get())) {
      tried += " " + node + " (no KMS)";
      continue;
    }
    if (has_connected_display(candidate.get())) {
      fd = std::move(candidate);
      path = node;
      return true;
    }
    if (fallback.empty()) fallback = node;
  }
  if (!fallback.empty()) {
    fd = open_node(fallback);
    path = fallback;
    if (fd) return true;
  }
  error = "no DRM device drives a display (" + (nodes.empty() ? std::string("no /dev/dri/card* found") : "tried:" + tried) +
          "); --drm-device names one";
  return false;
}

struct FbData {
  int fd;
  std::uint32_t fb;
};

void destroy_fb(gbm_bo* bo, void* data) {
  (void)bo;
  auto* fb = static_cast<FbData*>(data);
  if (fb->fb != 0) drmModeRmFB(fb->fd, fb->fb);
  delete fb;
}

class KmsPlatform final : public Platform {
 public:
  ~KmsPlatform() override {
    // The locked buffers go back first: Mesa frees a surface's buffers, locked or not, with its EGL
    // surface, and gbm_surface_release_buffer would then read freed memory.
    release_buffers();
    if (display_ != EGL_NO_DISPLAY) {
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (egl_surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, egl_surface_);
      if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    }
    if (surface_ != nullptr) gbm_surface_destroy(surface_);
    if (mode_blob_ != 0) drmModeDestroyPropertyBlob(fd_.get(), mode_blob_);
    // The display is terminated before GBM goes: EGL's GBM platform holds the device.
    if (display_ != EGL_NO_DISPLAY) eglTerminate(display_);
    if (gbm_ != nullptr) gbm_device_destroy(gbm_);
  }

  static std::unique_ptr<Platform> create(const Options& options, std::string& error);

  std::string_view name() const override { return "kms"; }
  std::string description() const override {
    std::string text = "DRM/KMS on " + device_path_ + " (" + driver_ + "), " + (atomic_ ? "atomic" : "legacy") +
                       " modesetting, " + (format_ == GBM_FORMAT_XRGB8888 ? "XRGB8888" : "ARGB8888");
    if (presenting_) text += ", " + connector_.name + " " + kms::describe(mode_);
    else text += ", " + reason_;
    return text;
  }
  std::vector<std::string> extensions_used() const override { return {gbm_extension_}; }
  void* proc_address(const char* name) const override { return reinterpret_cast<void*>(eglGetProcAddress(name)); }
  Size size() const override { return surface_size_; }
  unsigned framebuffer() const override { return 0; }
  bool srgb_framebuffer() const override { return false; }
  bool resize(Size size, std::string& error) override {
    if (size == surface_size_) return true;
    error = "kms: the surface is the display mode's size (" + std::to_string(surface_size_.width) + "x" +
            std::to_string(surface_size_.height) + "); --drm-mode chooses another";
    return false;
  }
  bool present() override;
  int event_fd() const override { return uevent_fd_.get(); }
  std::size_t drain_events(std::span<Event> out) override;
  bool presenting() const override { return presenting_; }
  std::string not_presenting_reason() const override { return presenting_ ? std::string() : reason_; }
  int poll_interval_ms() const override { return 100; }
  std::string last_error() const override { return last_error_; }
  bool capture_scanout(std::vector<std::uint8_t>& rgba, Size& size, std::string& error) override;

 private:
  // A flip that takes this long is not coming: the error path re-modesets. Far above any refresh
  // period, and above what a display under software emulation needs (about 10x slower than real time).
  static constexpr int kFlipTimeoutMs = 1000;
  static constexpr int kFlipTimeoutsBeforeGivingUp = 3;

  // Each commit's event carries its sequence number as user data; an event of a flip given up on
  // (timed out, then completed late) must not be taken for the one pending now.
  static thread_local KmsPlatform* handling_events_;
  static void on_flip(int fd, unsigned frame, unsigned sec, unsigned usec, void* data) {
    (void)fd;
    (void)frame;
    (void)sec;
    (void)usec;
    KmsPlatform* self = handling_events_;
    if (self != nullptr && self->flip_pending_ && reinterpret_cast<std::uintptr_t>(data) == self->flip_sequence_) self->flip_done();
  }
  void flip_done() {
    flip_pending_ = false;
    flip_timeouts_ = 0;
    if (shown_ != nullptr) gbm_surface_release_buffer(surface_, shown_);
    shown_ = pending_;
    pending_ = nullptr;
  }
  // A flip that did not complete in time: its buffer stays locked (it may be on screen or become so)
  // until a modeset puts a new one there; its event, should it come, is ignored.
  void abandon_flip() {
    flip_pending_ = false;
    ++flip_sequence_;
  }
  void* flip_user_data() const { return reinterpret_cast<void*>(static_cast<std::uintptr_t>(flip_sequence_)); }
  bool wait_for_flip(int timeout_ms);
  void release_buffers();
  std::uint32_t framebuffer_for(gbm_bo* bo, std::string& error);
  bool make_surface(Size size, std::string& error);
  bool set_up_output(const Probe& found, int connector_index, int mode_index, std::string& error);
  bool modeset(std::uint32_t fb, int& error_code);
  bool flip(std::uint32_t fb, int& error_code);
  // After an error that a new open of the device would clear: the player makes the platform anew.
  void request_remake(std::string reason) {
    reason_ = std::move(reason);
    last_error_ = reason_;
    push(EventType::remake);
  }
  // Reads the connectors and starts or stops presenting to match.
  void reprobe();
  void stop_presenting(std::string reason, bool retry);
  void push(EventType type) {
    if (queued_ == queue_.size()) return;  // a burst of hotplugs: the last state is what counts
    Event& event = queue_[queued_++];
    event = {};
    event.type = type;
    event.size = surface_size_;
  }
  void warn(std::string text) {
    if (text == last_error_) return;
    last_error_ = std::move(text);
    push(EventType::warning);
  }

  Fd fd_, uevent_fd_;
  std::string device_path_, driver_;
  gbm_device* gbm_ = nullptr;
  gbm_surface* surface_ = nullptr;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLConfig config_ = nullptr;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface egl_surface_ = EGL_NO_SURFACE;
  std::string gbm_extension_;
  std::uint32_t format_ = GBM_FORMAT_XRGB8888;
  bool atomic_ = false, modifiers_ = false;
  Size surface_size_;

  // What is driven: the options that choose it, and what they chose.
  std::string wanted_connector_;
  kms::ModeRequest wanted_mode_;
  Connector connector_;
  kms::Mode mode_;
  drmModeModeInfo raw_mode_{};
  std::uint32_t crtc_ = 0, plane_ = 0, mode_blob_ = 0, writeback_ = 0;
  struct {
    std::uint32_t connector_crtc = 0, crtc_mode = 0, crtc_active = 0, plane_fb = 0, plane_crtc = 0, src_x = 0, src_y = 0,
                  src_w = 0, src_h = 0, crtc_x = 0, crtc_y = 0, crtc_w = 0, crtc_h = 0;
  } props_;
  // What the last modeset drove, switched off when a hotplug moves the output elsewhere.
  std::uint32_t driven_connector_ = 0, driven_connector_crtc_prop_ = 0, driven_crtc_ = 0, driven_crtc_active_prop_ = 0,
                driven_crtc_mode_prop_ = 0, driven_plane_ = 0, driven_plane_fb_prop_ = 0, driven_plane_crtc_prop_ = 0;
  // Other planes (overlays, cursors) another client left on this CRTC: switched off at the modeset.
  struct OtherPlane {
    std::uint32_t id = 0, fb_prop = 0, crtc_prop = 0;
  };
  std::vector<OtherPlane> other_planes_;
  AtomicPtr request_{drmModeAtomicAlloc()};  // for modesets; a flip is one ioctl on arrays of its own

  bool presenting_ = false, needs_modeset_ = true, flip_pending_ = false;
  gbm_bo* shown_ = nullptr;    // on the screen now
  gbm_bo* pending_ = nullptr;  // queued to flip at the next vblank (or a flip given up on)
  std::uint64_t flip_sequence_ = 1;
  int flip_timeouts_ = 0;  // in a row: reset only when a flip's event arrives
  std::string reason_ = "no display", last_error_;
  // After an error (master lost, a refused modeset) the output is tried again at retry_at_, the
  // wait doubling up to 5 s; a uevent tries at once.
  bool retry_pending_ = false;
  SteadyClock::time_point retry_at_{};
  std::chrono::milliseconds backoff_{100};
  SteadyClock::time_point next_look_{};  // without hotplug events: when the connectors are read again

  std::array<Event, 16> queue_{};
  std::size_t queued_ = 0;
};

thread_local KmsPlatform* KmsPlatform::handling_events_ = nullptr;

std::unique_ptr<Platform> KmsPlatform::create(const Options& options, std::string& error) {
  auto platform = std::unique_ptr<KmsPlatform>(new KmsPlatform());
  KmsPlatform& self = *platform;
  self.wanted_connector_ = options.drm_connector;
  if (!kms::parse_mode_request(options.drm_mode, self.wanted_mode_, error)) return nullptr;
  if (options.drm_atomic != "auto" && options.drm_atomic != "no") {
    error = "--drm-atomic: expected auto or no, got '" + options.drm_atomic + "'";
    return nullptr;
  }
  std::string why;
  if (!open_device(options.drm_device, self.fd_, self.device_path_, why)) {
    error = "kms: " + why;
    return nullptr;
  }
  const int fd = self.fd_.get();
  if (auto* version = drmGetVersion(fd)) {
    self.driver_ = version->name;
    drmFreeVersion(version);
  }
  drmSetClientCap(fd, DRM_CLIENT_CAP_UNIVERSAL_PLANES, 1);
  self.atomic_ = options.drm_atomic == "auto" && drmSetClientCap(fd, DRM_CLIENT_CAP_ATOMIC, 1) == 0;
  if (self.atomic_) drmSetClientCap(fd, DRM_CLIENT_CAP_WRITEBACK_CONNECTORS, 1);
  std::uint64_t cap = 0;
  // Framebuffers get a modifier only where the driver takes them and the buffer has a real one:
  // vkms refuses DRM_FORMAT_MOD_INVALID, which is what Mesa's software buffers report.
  self.modifiers_ = drmGetCap(fd, DRM_CAP_ADDFB2_MODIFIERS, &cap) == 0 && cap != 0;

  self.gbm_ = gbm_create_device(fd);
  if (self.gbm_ == nullptr) {
    error = "kms: gbm_create_device on " + self.device_path_ + " failed (" + errno_text(errno) + ")";
    return nullptr;
  }
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  self.gbm_extension_ = egl::has_extension(client, "EGL_KHR_platform_gbm") ? "EGL_KHR_platform_gbm" : "EGL_MESA_platform_gbm";
  if (get_platform_display == nullptr || !egl::has_extension(client, self.gbm_extension_.c_str())) {
    error = "kms: the EGL library offers no GBM platform (EGL_KHR_platform_gbm or EGL_MESA_platform_gbm)";
    return nullptr;
  }
  self.display_ = get_platform_display(EGL_PLATFORM_GBM_KHR, self.gbm_, nullptr);
  EGLint major = 0, minor = 0;
  if (self.display_ == EGL_NO_DISPLAY || !egl::initialize(self.display_, major, minor, why)) {
    error = "kms: no EGL display on GBM for " + self.device_path_ + (why.empty() ? "" : " (" + why + ")");
    return nullptr;
  }
  // A window config whose native visual is the scanout format: XRGB8888, else ARGB8888.
  const EGLint wanted[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT_KHR, EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RED_SIZE, 8,
                           EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_NONE};
  EGLint count = 0;
  eglChooseConfig(self.display_, wanted, nullptr, 0, &count);
  std::vector<EGLConfig> configs(static_cast<size_t>(std::max(count, 0)));
  if (count > 0) eglChooseConfig(self.display_, wanted, configs.data(), count, &count);
  for (std::uint32_t format : {GBM_FORMAT_XRGB8888, GBM_FORMAT_ARGB8888}) {
    for (EGLConfig config : configs) {
      EGLint visual = 0;
      if (eglGetConfigAttrib(self.display_, config, EGL_NATIVE_VISUAL_ID, &visual) && static_cast<std::uint32_t>(visual) == format) {
        self.config_ = config;
        self.format_ = format;
        break;
      }
    }
    if (self.config_ != nullptr) break;
  }
  if (self.config_ == nullptr) {
    error = "kms: no EGL config renders OpenGL ES 3 into an XRGB8888 or ARGB8888 GBM surface";
    return nullptr;
  }
  self.context_ = egl::create_context(self.display_, self.config_, major, minor, options.debug_context, why);
  if (self.context_ == EGL_NO_CONTEXT) {
    error = "kms: " + why;
    return nullptr;
  }

  Probe found;
  if (!probe(fd, found, why)) {
    error = "kms: " + self.device_path_ + ": " + why;
    return nullptr;
  }
  self.writeback_ = found.writeback;
  bool waiting = false;
  const int index = kms::choose_connector(found.connectors, self.wanted_connector_, waiting, why);
  if (index < 0 && !waiting) {
    error = "kms: " + why + "\n" + kms::describe_connectors(self.device_path_, found.connectors);
    return nullptr;
  }
  int mode_index = -1;
  if (index >= 0) {
    mode_index = kms::choose_mode(found.connectors[static_cast<size_t>(index)], self.wanted_mode_, why);
    if (mode_index < 0) {
      error = "kms: " + why + "\n" + kms::describe_connectors(self.device_path_, found.connectors);
      return nullptr;
    }
  }
  // Without a display the context still needs a surface to be current on; it is replaced by one of
  // the mode's size when a display comes.
  if (!self.make_surface(index >= 0 ? Size{found.connectors[static_cast<size_t>(index)].modes[static_cast<size_t>(mode_index)].width,
                                           found.connectors[static_cast<size_t>(index)].modes[static_cast<size_t>(mode_index)].height}
                                    : options.size,
                         error))
    return nullptr;
  if (index >= 0) {
    if (!self.set_up_output(found, index, mode_index, error)) return nullptr;
    self.presenting_ = true;
  } else {
    self.reason_ = self.wanted_connector_ == "auto" ? "no display connected"
                                                   : "no display connected to " + self.wanted_connector_;
  }
  self.uevent_fd_.reset(uevent::open_socket());
  if (!self.uevent_fd_) self.warn("kms: no hotplug events (netlink uevent socket: " + errno_text(errno) + "); displays are looked for every second");
  return platform;
}

bool KmsPlatform::make_surface(Size size, std::string& error) {
  gbm_surface* surface = gbm_surface_create(gbm_, static_cast<std::uint32_t>(size.width), static_cast<std::uint32_t>(size.height),
                                            format_, GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
  if (surface == nullptr) {
    error = "kms: gbm_surface_create " + std::to_string(size.width) + "x" + std::to_string(size.height) + " failed (" +
            errno_text(errno) + ")";
    return false;
  }
  EGLSurface egl_surface = eglCreateWindowSurface(display_, config_, reinterpret_cast<EGLNativeWindowType>(surface), nullptr);
  if (egl_surface == EGL_NO_SURFACE || !eglMakeCurrent(display_, egl_surface, egl_surface, context_)) {
    error = "kms: no EGL window surface on the GBM surface (" + egl::error_name(eglGetError()) + ")";
    if (egl_surface != EGL_NO_SURFACE) eglDestroySurface(display_, egl_surface);
    gbm_surface_destroy(surface);
    return false;
  }
  // The old surface's buffers go back before its EGL surface (which frees them) and its GBM surface.
  release_buffers();
  if (egl_surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, egl_surface_);
  if (surface_ != nullptr) gbm_surface_destroy(surface_);
  surface_ = surface;
  egl_surface_ = egl_surface;
  surface_size_ = size;
  needs_modeset_ = true;
  return true;
}

void KmsPlatform::release_buffers() {
  if (flip_pending_ && !wait_for_flip(kFlipTimeoutMs)) abandon_flip();
  if (surface_ == nullptr) return;
  if (pending_ != nullptr) gbm_surface_release_buffer(surface_, pending_);
  if (shown_ != nullptr) gbm_surface_release_buffer(surface_, shown_);
  pending_ = shown_ = nullptr;
}

bool KmsPlatform::set_up_output(const Probe& found, int connector_index, int mode_index, std::string& error) {
  const int fd = fd_.get();
  const Connector& connector = found.connectors[static_cast<size_t>(connector_index)];
  int crtc_index = -1;
  std::uint32_t crtc = 0;
  if (!find_crtc(fd, connector.id, crtc, crtc_index)) {
    error = "kms: no CRTC can drive " + connector.name;
    return false;
  }
  std::uint32_t plane = 0;
  std::vector<OtherPlane> others;
  if (atomic_) {
    plane = find_primary_plane(fd, crtc_index);
    props_.connector_crtc = property_id(fd, connector.id, DRM_MODE_OBJECT_CONNECTOR, "CRTC_ID");
    props_.crtc_mode = property_id(fd, crtc, DRM_MODE_OBJECT_CRTC, "MODE_ID");
    props_.crtc_active = property_id(fd, crtc, DRM_MODE_OBJECT_CRTC, "ACTIVE");
    props_.plane_fb = property_id(fd, plane, DRM_MODE_OBJECT_PLANE, "FB_ID");
    props_.plane_crtc = property_id(fd, plane, DRM_MODE_OBJECT_PLANE, "CRTC_ID");
    props_.src_x = property_id(fd, plane, DRM_MODE_OBJECT_PLANE, "SRC_X");
    props_.src_y = property_id(fd, plane, DRM_MODE_OBJECT_PLANE, "SRC_Y");
    props_.src_w = property_id(fd, plane, DRM_MODE_OBJECT_PLANE, "SRC_W");
    props_.src_h = property_id(fd, plane, DRM_MODE_OBJECT_PLANE, "SRC_H");
    props_.crtc_x = property_id(fd, plane, DRM_MODE_OBJECT_PLANE, "CRTC_X");
    props_.crtc_y = property_id(fd, plane, DRM_MODE_OBJECT_PLANE, "CRTC_Y");
    props_.crtc_w = property_id(fd, plane, DRM_MODE_OBJECT_PLANE, "CRTC_W");
    props_.crtc_h = property_id(fd, plane, DRM_MODE_OBJECT_PLANE, "CRTC_H");
    const std::uint32_t all[] = {props_.connector_crtc, props_.crtc_mode, props_.crtc_active, props_.plane_fb, props_.plane_crtc,
                                 props_.src_x,          props_.src_y,     props_.src_w,       props_.src_h,    props_.crtc_x,
                                 props_.crtc_y,         props_.crtc_w,    props_.crtc_h};
    if (plane == 0 || !request_ || std::find(std::begin(all), std::end(all), 0u) != std::end(all)) {
      // A driver whose atomic interface lacks what a modeset needs: legacy does it.
      atomic_ = false;
      plane = 0;
    }
    if (PlaneResourcesPtr planes{drmModeGetPlaneResources(fd)}; atomic_ && planes) {
      for (std::uint32_t i = 0; i < planes->count_planes; ++i) {
        const std::uint32_t id = planes->planes[i];
        if (id == plane) continue;
        PlanePtr other(drmModeGetPlane(fd, id));
        if (other && other->crtc_id == crtc)
          others.push_back({id, property_id(fd, id, DRM_MODE_OBJECT_PLANE, "FB_ID"), property_id(fd, id, DRM_MODE_OBJECT_PLANE, "CRTC_ID")});
      }
    }
  }
  const drmModeModeInfo& raw = found.raw_modes[static_cast<size_t>(connector_index)][static_cast<size_t>(mode_index)];
  std::uint32_t blob = 0;
  if (atomic_ && drmModeCreatePropertyBlob(fd, &raw, sizeof raw, &blob) != 0) {
    error = "kms: the mode " + kms::describe(connector.modes[static_cast<size_t>(mode_index)]) + " could not be made a property blob (" +
            errno_text(errno) + ")";
    return false;
  }
  const kms::Mode mode = connector.modes[static_cast<size_t>(mode_index)];
  if (mode.width != surface_size_.width || mode.height != surface_size_.height) {
    if (!make_surface({mode.width, mode.height}, error)) {
      if (blob != 0) drmModeDestroyPropertyBlob(fd, blob);
      return false;
    }
    push(EventType::resized);
  }
  if (mode_blob_ != 0) drmModeDestroyPropertyBlob(fd, mode_blob_);
  mode_blob_ = blob;
  connector_ = connector;
  mode_ = mode;
  raw_mode_ = raw;
  crtc_ = crtc;
  plane_ = plane;
  other_planes_ = std::move(others);
  needs_modeset_ = true;
  return true;
}

std::uint32_t KmsPlatform::framebuffer_for(gbm_bo* bo, std::string& error) {
  if (auto* cached = static_cast<FbData*>(gbm_bo_get_user_data(bo))) return cached->fb;
  std::uint32_t handles[4] = {}, strides[4] = {}, offsets[4] = {};
  std::uint64_t modifiers[4] = {};
  const int planes = std::clamp(gbm_bo_get_plane_count(bo), 1, 4);
  const std::uint64_t modifier = gbm_bo_get_modifier(bo);
  for (int p = 0; p < planes; ++p) {
    handles[p] = gbm_bo_get_handle_for_plane(bo, p).u32;
    strides[p] = gbm_bo_get_stride_for_plane(bo, p);
    offsets[p] = gbm_bo_get_offset(bo, p);
    modifiers[p] = modifier;
  }
  const std::uint32_t width = gbm_bo_get_width(bo), height = gbm_bo_get_height(bo), format = gbm_bo_get_format(bo);
  const bool with_modifier = modifiers_ && modifier != DRM_FORMAT_MOD_INVALID;
  std::uint32_t fb = 0;
  const int result = with_modifier ? drmModeAddFB2WithModifiers(fd_.get(), width, height, format, handles, strides, offsets, modifiers,
                                                                &fb, DRM_MODE_FB_MODIFIERS)
                                   : drmModeAddFB2(fd_.get(), width, height, format, handles, strides, offsets, &fb, 0);
  if (result != 0) {
    char fourcc[5] = {static_cast<char>(format), static_cast<char>(format >> 8), static_cast<char>(format >> 16),
                      static_cast<char>(format >> 24), '\0'};
    char modifier_text[32];
    std::snprintf(modifier_text, sizeof modifier_text, "0x%016llx", static_cast<unsigned long long>(modifier));
    error = "kms: " + device_path_ + " refused a " + std::to_string(width) + "x" + std::to_string(height) + " " + fourcc +
            " framebuffer with " + std::to_string(planes) + " plane(s), " +
            (with_modifier ? std::string("modifier ") + modifier_text : std::string("no modifier")) + " (drmModeAddFB2: " +
            errno_text(errno) + ")";
    return 0;
  }
  gbm_bo_set_user_data(bo, new FbData{fd_.get(), fb}, destroy_fb);
  return fb;
}

bool KmsPlatform::modeset(std::uint32_t fb, int& error_code) {
  const int fd = fd_.get();
  int result = 0;
  if (atomic_) {
    drmModeAtomicReq* request = request_.get();
    drmModeAtomicSetCursor(request, 0);
    // What a hotplug moved the output away from is switched off in the same commit.
    if (driven_connector_ != 0 && driven_connector_ != connector_.id)
      drmModeAtomicAddProperty(request, driven_connector_, driven_connector_crtc_prop_, 0);
    if (driven_crtc_ != 0 && driven_crtc_ != crtc_) {
      drmModeAtomicAddProperty(request, driven_plane_, driven_plane_fb_prop_, 0);
      drmModeAtomicAddProperty(request, driven_plane_, driven_plane_crtc_prop_, 0);
      drmModeAtomicAddProperty(request, driven_crtc_, driven_crtc_active_prop_, 0);
      drmModeAtomicAddProperty(request, driven_crtc_, driven_crtc_mode_prop_, 0);
    }
    for (const OtherPlane& other : other_planes_) {
      drmModeAtomicAddProperty(request, other.id, other.fb_prop, 0);
      drmModeAtomicAddProperty(request, other.id, other.crtc_prop, 0);
    }
    const auto w = static_cast<std::uint64_t>(mode_.width), h = static_cast<std::uint64_t>(mode_.height);
    drmModeAtomicAddProperty(request, connector_.id, props_.connector_crtc, crtc_);
    drmModeAtomicAddProperty(request, crtc_, props_.crtc_mode, mode_blob_);
    drmModeAtomicAddProperty(request, crtc_, props_.crtc_active, 1);
    drmModeAtomicAddProperty(request, plane_, props_.plane_fb, fb);
    drmModeAtomicAddProperty(request, plane_, props_.plane_crtc, crtc_);
    drmModeAtomicAddProperty(request, plane_, props_.src_x, 0);
    drmModeAtomicAddProperty(request, plane_, props_.src_y, 0);
    drmModeAtomicAddProperty(request, plane_, props_.src_w, w << 16);
    drmModeAtomicAddProperty(request, plane_, props_.src_h, h << 16);
    drmModeAtomicAddProperty(request, plane_, props_.crtc_x, 0);
    drmModeAtomicAddProperty(request, plane_, props_.crtc_y, 0);
    drmModeAtomicAddProperty(request, plane_, props_.crtc_w, w);
    drmModeAtomicAddProperty(request, plane_, props_.crtc_h, h);
    result = drmModeAtomicCommit(fd, request, DRM_MODE_ATOMIC_ALLOW_MODESET, nullptr);
  } else {
    if (driven_crtc_ != 0 && driven_crtc_ != crtc_) drmModeSetCrtc(fd, driven_crtc_, 0, 0, 0, nullptr, 0, nullptr);
    std::uint32_t connector = connector_.id;
    result = drmModeSetCrtc(fd, crtc_, fb, 0, 0, &connector, 1, &raw_mode_);
  }
  error_code = result == 0 ? 0 : errno;
  if (result == 0) {
    other_planes_.clear();
    driven_connector_ = connector_.id;
    driven_connector_crtc_prop_ = props_.connector_crtc;
    driven_crtc_ = crtc_;
    driven_crtc_active_prop_ = props_.crtc_active;
    driven_crtc_mode_prop_ = props_.crtc_mode;
    driven_plane_ = plane_;
    driven_plane_fb_prop_ = props_.plane_fb;
    driven_plane_crtc_prop_ = props_.plane_crtc;
  }
  return result == 0;
}

bool KmsPlatform::flip(std::uint32_t fb, int& error_code) {
  int result = 0;
  if (atomic_) {
    // One plane, one property: the ioctl on arrays of its own, since libdrm's commit allocates.
    std::uint32_t objects[1] = {plane_}, counts[1] = {1}, properties[1] = {props_.plane_fb};
    std::uint64_t values[1] = {fb};
    drm_mode_atomic atomic{};
    // No in-fence: the buffer is complete when eglSwapBuffers returns on implicitly synchronised
    // drivers, and llvmpipe has no EGL_ANDROID_native_fence_sync to make one.
    atomic.flags = DRM_MODE_ATOMIC_NONBLOCK | DRM_MODE_PAGE_FLIP_EVENT;
    atomic.count_objs = 1;
    atomic.objs_ptr = reinterpret_cast<std::uintptr_t>(objects);
    atomic.count_props_ptr = reinterpret_cast<std::uintptr_t>(counts);
    atomic.props_ptr = reinterpret_cast<std::uintptr_t>(properties);
    atomic.prop_values_ptr = reinterpret_cast<std::uintptr_t>(values);
    atomic.user_data = flip_sequence_;
    result = drmIoctl(fd_.get(), DRM_IOCTL_MODE_ATOMIC, &atomic);
  } else {
    result = drmModePageFlip(fd_.get(), crtc_, fb, DRM_MODE_PAGE_FLIP_EVENT, flip_user_data());
  }
  error_code = result == 0 ? 0 : errno;
  return result == 0;
}

bool KmsPlatform::wait_for_flip(int timeout_ms) {
  drmEventContext handlers{};
  handlers.version = 2;
  handlers.page_flip_handler = on_flip;
  const SteadyClock::time_point deadline = SteadyClock::now() + std::chrono::milliseconds(timeout_ms);
  handling_events_ = this;
  while (flip_pending_) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - SteadyClock::now()).count();
    if (left < 0) break;
    pollfd wait{fd_.get(), POLLIN, 0};
    const int ready = poll(&wait, 1, static_cast<int>(left));
    if (ready < 0 && errno != EINTR) break;
    if (ready > 0) drmHandleEvent(fd_.get(), &handlers);
  }
  handling_events_ = nullptr;
  return !flip_pending_;
}

void KmsPlatform::stop_presenting(std::string reason, bool retry) {
  if (flip_pending_ && !wait_for_flip(kFlipTimeoutMs)) abandon_flip();
  reason_ = std::move(reason);
  retry_pending_ = retry;
  if (retry) retry_at_ = SteadyClock::now() + backoff_;
  if (presenting_) {
    presenting_ = false;
    push(EventType::display_lost);
  }
}

bool KmsPlatform::present() {
  if (!presenting_) return true;
  if (!eglSwapBuffers(display_, egl_surface_)) {
    last_error_ = "kms: eglSwapBuffers failed (" + egl::error_name(eglGetError()) + ")";
    return false;
  }
  gbm_bo* bo = gbm_surface_lock_front_buffer(surface_);
  if (bo == nullptr) {
    last_error_ = "kms: no front buffer after eglSwapBuffers (gbm_surface_lock_front_buffer)";
    return false;
  }
  std::string error;
  const std::uint32_t fb = framebuffer_for(bo, error);
  if (fb == 0) {
    gbm_surface_release_buffer(surface_, bo);
    warn(error);
    stop_presenting("the display takes no framebuffer of this surface: " + error, true);
    return true;
  }
  // The previous frame's flip first: its completion frees the buffer shown before it, and is what
  // paces the loop to the display's refresh.
  if (flip_pending_ && !wait_for_flip(kFlipTimeoutMs)) {
    abandon_flip();
    needs_modeset_ = true;
    warn("kms: a page flip on " + connector_.name + " did not complete within " + std::to_string(kFlipTimeoutMs) +
         " ms; setting the mode again");
    if (++flip_timeouts_ >= kFlipTimeoutsBeforeGivingUp) {
      gbm_surface_release_buffer(surface_, bo);
      last_error_ = "kms: " + std::to_string(kFlipTimeoutsBeforeGivingUp) + " page flips in a row on " + connector_.name + " (" +
                    device_path_ + ") did not complete within " + std::to_string(kFlipTimeoutMs) + " ms";
      return false;
    }
  }
  int code = 0;
  const bool setting_mode = needs_modeset_;
  if (setting_mode) {
    if (modeset(fb, code)) {
      needs_modeset_ = false;
      backoff_ = std::chrono::milliseconds(100);
      // The buffers of the old mode (and of a flip given up on) leave the screen with this commit.
      if (shown_ != nullptr) gbm_surface_release_buffer(surface_, shown_);
      if (pending_ != nullptr) gbm_surface_release_buffer(surface_, pending_);
      shown_ = bo;
      pending_ = nullptr;
      return true;
    }
  } else if (flip(fb, code)) {
    pending_ = bo;
    flip_pending_ = true;
    return true;
  }
  gbm_surface_release_buffer(surface_, bo);
  if (code == EBUSY) return true;  // the previous commit is still in flight: this frame is dropped
  if (code == EACCES || code == EPERM) {
    // Another client (a VT switch, a display server) holds DRM master: wait for it to let go.
    needs_modeset_ = true;
    stop_presenting("another process holds the display (DRM master)", true);
    return true;
  }
  const std::string what = std::string(setting_mode ? (atomic_ ? "an atomic modeset to " : "drmModeSetCrtc to ")
                                                    : (atomic_ ? "an atomic page flip on " : "drmModePageFlip on ")) +
                           connector_.name + " " + kms::describe(mode_) + " failed (" + errno_text(code) + ")";
  warn("kms: " + what);
  needs_modeset_ = true;
  stop_presenting(std::string(setting_mode ? "the display refused the mode: " : "the display refused a page flip: ") + what, true);
  return true;
}

void KmsPlatform::reprobe() {
  Probe found;
  std::string why;
  if (!probe(fd_.get(), found, why)) {
    stop_presenting(why, true);
    return;
  }
  writeback_ = found.writeback;
  bool waiting = false;
  const int index = kms::choose_connector(found.connectors, wanted_connector_, waiting, why);
  if (index < 0) {
    stop_presenting(waiting ? (wanted_connector_ == "auto" ? "no display connected" : "no display connected to " + wanted_connector_) : why,
                    false);
    return;
  }
  const int mode_index = kms::choose_mode(found.connectors[static_cast<size_t>(index)], wanted_mode_, why);
  if (mode_index < 0) {
    warn("kms: " + why);
    stop_presenting(why, false);
    return;
  }
  const Connector& connector = found.connectors[static_cast<size_t>(index)];
  const drmModeModeInfo& raw = found.raw_modes[static_cast<size_t>(index)][static_cast<size_t>(mode_index)];
  const bool same = presenting_ && connector.id == connector_.id && std::memcmp(&raw, &raw_mode_, sizeof raw) == 0;
  if (same) {
    // The same display and mode; a link the driver marks bad (a DP replug) still wants a modeset.
    if (property_value(fd_.get(), connector.id, DRM_MODE_OBJECT_CONNECTOR, "link-status", DRM_MODE_LINK_STATUS_GOOD) ==
        DRM_MODE_LINK_STATUS_BAD)
      needs_modeset_ = true;
    return;
  }
  if (!set_up_output(found, index, mode_index, why)) {
    warn(why);
    stop_presenting(why, true);
    return;
  }
  presenting_ = true;
  retry_pending_ = false;
  push(EventType::display_found);
}

std::size_t KmsPlatform::drain_events(std::span<Event> out) {
  bool changed = false;
  const SteadyClock::time_point now = SteadyClock::now();
  if (uevent_fd_) {
    char buffer[4096];
    for (;;) {
      const ssize_t length = recv(uevent_fd_.get(), buffer, sizeof buffer, MSG_DONTWAIT);
      if (length < 0 && errno == ENOBUFS) {
        changed = true;  // events were dropped: whatever they said, the connectors tell now
        continue;
      }
      if (length <= 0) break;
      uevent::Message message;
      if (uevent::parse({buffer, static_cast<size_t>(length)}, message) && uevent::is_drm_change_of(message, device_path_))
        changed = true;
    }
  } else if (now >= next_look_) {
    changed = true;  // no hotplug events: the connectors are read every second
    next_look_ = now + std::chrono::seconds(1);
  }
  if (!changed && retry_pending_ && now >= retry_at_) {
    if (reason_.find("DRM master") != std::string::npos && !drmIsMaster(fd_.get()) && drmSetMaster(fd_.get()) != 0) {
      // Without CAP_SYS_ADMIN the kernel gives master back only to a file that held it. Whether a
      // new open would get it says whether the other client is gone.
      Fd probe_fd = open_node(device_path_);
      if (probe_fd && drmIsMaster(probe_fd.get())) {
        retry_pending_ = false;
        request_remake("kms: DRM master of " + device_path_ + " is free again, but only a new open of the device can have it");
      } else {
        backoff_ = std::min(backoff_ * 2, std::chrono::milliseconds(5000));
        retry_at_ = now + backoff_;
      }
    } else {
      changed = true;
      needs_modeset_ = true;
      backoff_ = std::min(backoff_ * 2, std::chrono::milliseconds(5000));
    }
  }
  if (changed) {
    const bool was_presenting = presenting_;
    reprobe();
    if (presenting_ && !was_presenting) needs_modeset_ = true;
  }
  const std::size_t n = std::min(queued_, out.size());
  std::copy_n(queue_.begin(), n, out.begin());
  std::copy(queue_.begin() + static_cast<std::ptrdiff_t>(n), queue_.begin() + static_cast<std::ptrdiff_t>(queued_), queue_.begin());
  queued_ -= n;
  return n;
}

bool KmsPlatform::capture_scanout(std::vector<std::uint8_t>& rgba, Size& size, std::string& error) {
  if (!atomic_) {
    error = "kms: capturing the scanout needs atomic modesetting (the driver lacks it, or --drm-atomic no)";
    return false;
  }
  if (writeback_ == 0) {
    error = "kms: " + device_path_ + " (" + driver_ + ") has no writeback connector to capture the scanout with";
    return false;
  }
  if (!presenting_ || shown_ == nullptr) {
    error = "kms: nothing is shown to capture (" + (presenting_ ? std::string("no frame presented yet") : reason_) + ")";
    return false;
  }
  if (flip_pending_ && !wait_for_flip(kFlipTimeoutMs)) {
    error = "kms: the last page flip did not complete within " + std::to_string(kFlipTimeoutMs) + " ms";
    return false;
  }
  const int fd = fd_.get();
  const std::uint32_t width = static_cast<std::uint32_t>(mode_.width), height = static_cast<std::uint32_t>(mode_.height);
  const std::string what = "the writeback connector on CRTC " + std::to_string(crtc_) + " at " + std::to_string(width) + "x" +
                           std::to_string(height) + " XRGB8888";
  std::uint32_t handle = 0, pitch = 0, fb = 0;
  std::uint64_t bytes = 0, offset = 0;
  if (drmModeCreateDumbBuffer(fd, width, height, 32, 0, &handle, &pitch, &bytes) != 0) {
    error = "kms: no dumb buffer for " + what + " (" + errno_text(errno) + ")";
    return false;
  }
  const std::uint32_t handles[4] = {handle}, pitches[4] = {pitch}, offsets[4] = {};
  bool ok = drmModeAddFB2(fd, width, height, DRM_FORMAT_XRGB8888, handles, pitches, offsets, &fb, 0) == 0;
  if (!ok) error = "kms: no framebuffer for " + what + " (drmModeAddFB2: " + errno_text(errno) + ")";
  const std::uint32_t crtc_prop = property_id(fd, writeback_, DRM_MODE_OBJECT_CONNECTOR, "CRTC_ID");
  const std::uint32_t fb_prop = property_id(fd, writeback_, DRM_MODE_OBJECT_CONNECTOR, "WRITEBACK_FB_ID");
  const std::uint32_t fence_prop = property_id(fd, writeback_, DRM_MODE_OBJECT_CONNECTOR, "WRITEBACK_OUT_FENCE_PTR");
  std::int32_t fence = -1;
  bool detached_display = false;
  if (ok) {
    // Beside the display where the driver can clone; where it cannot (vkms on 6.1 refuses two
    // encoders on one CRTC), the display connector is detached for the capture: the CRTC still
    // composes the same planes, so what the writeback sees is what was being scanned out.
    for (const bool detach : {false, true}) {
      AtomicPtr request(drmModeAtomicAlloc());
      if (detach) drmModeAtomicAddProperty(request.get(), connector_.id, props_.connector_crtc, 0);
      drmModeAtomicAddProperty(request.get(), writeback_, crtc_prop, crtc_);
      drmModeAtomicAddProperty(request.get(), writeback_, fb_prop, fb);
      drmModeAtomicAddProperty(request.get(), writeback_, fence_prop, reinterpret_cast<std::uintptr_t>(&fence));
      ok = drmModeAtomicCommit(fd, request.get(), DRM_MODE_ATOMIC_ALLOW_MODESET, nullptr) == 0;
      detached_display = detach;
      if (ok || errno != EINVAL) break;
    }
    if (!ok) error = "kms: the commit attaching " + what + " was refused (" + errno_text(errno) + "), beside " + connector_.name + " and without it";
  }
  if (ok && fence >= 0) {
    pollfd wait{fence, POLLIN, 0};
    ok = poll(&wait, 1, kFlipTimeoutMs * 5) == 1;
    if (!ok) error = "kms: " + what + " did not complete within " + std::to_string(kFlipTimeoutMs * 5) + " ms";
  }
  if (fence >= 0) close(fence);
  if (ok) {
    ok = drmModeMapDumbBuffer(fd, handle, &offset) == 0;
    void* mapped = ok ? mmap(nullptr, bytes, PROT_READ, MAP_SHARED, fd, static_cast<off_t>(offset)) : MAP_FAILED;
    if (mapped == MAP_FAILED) {
      ok = false;
      error = "kms: cannot map the buffer of " + what + " (" + errno_text(errno) + ")";
    } else {
      rgba.resize(static_cast<size_t>(width) * height * 4);
      const auto* source = static_cast<const std::uint8_t*>(mapped);
      for (std::uint32_t y = 0; y < height; ++y)
        for (std::uint32_t x = 0; x < width; ++x) {
          const std::uint8_t* in = source + static_cast<size_t>(y) * pitch + x * 4;  // XRGB8888: B, G, R, X in memory
          std::uint8_t* pixel = &rgba[(static_cast<size_t>(y) * width + x) * 4];
          pixel[0] = in[2];
          pixel[1] = in[1];
          pixel[2] = in[0];
          pixel[3] = 255;
        }
      munmap(mapped, bytes);
      size = {mode_.width, mode_.height};
    }
  }
  // Detached again (and the display attached again), so the next flips commit the primary plane alone.
  AtomicPtr restore(drmModeAtomicAlloc());
  drmModeAtomicAddProperty(restore.get(), writeback_, crtc_prop, 0);
  drmModeAtomicAddProperty(restore.get(), writeback_, fb_prop, 0);
  if (detached_display) drmModeAtomicAddProperty(restore.get(), connector_.id, props_.connector_crtc, crtc_);
  if (drmModeAtomicCommit(fd, restore.get(), DRM_MODE_ATOMIC_ALLOW_MODESET, nullptr) != 0) needs_modeset_ = true;
  if (fb != 0) drmModeRmFB(fd, fb);
  drmModeDestroyDumbBuffer(fd, handle);
  return ok;
}

}  // namespace

std::unique_ptr<Platform> create_kms(const Options& options, std::string& error) { return KmsPlatform::create(options, error); }

bool find_kms_device(std::string& path) {
  for (const std::string& node : primary_nodes()) {
    Fd fd = open_node(node);
    if (fd && has_kms(fd.get())) {
      path = node;
      return true;
    }
  }
  return false;
}

bool describe_kms_outputs(const Options& options, std::string& text, std::string& error) {
  std::vector<std::string> nodes;
  if (!options.drm_device.empty()) nodes.push_back(options.drm_device);
  else nodes = primary_nodes();
  if (nodes.empty()) {
    error = "kms: no DRM device (no /dev/dri/card*)";
    return false;
  }
  text.clear();
  for (const std::string& node : nodes) {
    Fd fd = open_node(node);
    if (!fd && !options.drm_device.empty()) {
      error = "kms: --drm-device: cannot open " + node + " (" + errno_text(errno) + ")";
      return false;
    }
    if (!fd) {
      text += node + ": cannot open (" + errno_text(errno) + ")\n";
      continue;
    }
    drmSetClientCap(fd.get(), DRM_CLIENT_CAP_UNIVERSAL_PLANES, 1);
    const bool atomic = drmSetClientCap(fd.get(), DRM_CLIENT_CAP_ATOMIC, 1) == 0;
    if (atomic) drmSetClientCap(fd.get(), DRM_CLIENT_CAP_WRITEBACK_CONNECTORS, 1);
    Probe found;
    std::string why;
    if (!probe(fd.get(), found, why)) {
      text += node + ": " + why + "\n";
      continue;
    }
    text += kms::describe_connectors(node + (atomic ? " (atomic)" : " (legacy)"), found.connectors);
    if (found.writeback != 0) text += "  and a writeback connector (captures what is shown)\n";
  }
  return true;
}

}  // namespace platform
