#include "backends.h"

#include <dlfcn.h>

#include <vector>

namespace platform {
namespace {

// From GL/osmesa.h, which cannot be included beside the GLES headers. OSMesa is opened with
// dlopen(RTLD_LOCAL) so its gl* exports never clash with libGLESv2's.
using OSMesaContext = void*;
constexpr int kOsmesaRgba = 0x1908;  // GL_RGBA
constexpr int kOsmesaFormat = 0x22, kOsmesaDepthBits = 0x30, kOsmesaStencilBits = 0x31, kOsmesaAccumBits = 0x32,
              kOsmesaProfile = 0x33, kOsmesaCoreProfile = 0x34, kOsmesaMajor = 0x36, kOsmesaMinor = 0x37;
using CreateContextAttribs = OSMesaContext (*)(const int*, OSMesaContext);
using DestroyContext = void (*)(OSMesaContext);
using MakeCurrent = unsigned char (*)(OSMesaContext, void*, unsigned, int, int);
using GetProcAddress = void* (*)(const char*);

struct OsmesaLibrary {
  void* handle = nullptr;
  CreateContextAttribs create = nullptr;
  DestroyContext destroy = nullptr;
  MakeCurrent make_current = nullptr;
  GetProcAddress get_proc = nullptr;
};

// The surface is OSMesa's own colour buffer (framebuffer 0). It has no sRGB encoding, so the
// present pass encodes in the shader.
class OsmesaPlatform final : public Platform {
 public:
  OsmesaPlatform(OsmesaLibrary library, OSMesaContext context) : library_(library), context_(context) {}
  ~OsmesaPlatform() override {
    library_.destroy(context_);
    // The library stays loaded: Mesa's atexit handlers still point into it.
  }
  std::string_view name() const override { return "osmesa"; }
  std::string description() const override { return "OSMesa, desktop OpenGL 4.5 core profile"; }
  std::vector<std::string> extensions_used() const override { return {"OSMesaCreateContextAttribs"}; }
  void* proc_address(const char* name) const override { return library_.get_proc(name); }
  Size size() const override { return size_; }
  unsigned framebuffer() const override { return 0; }
  bool srgb_framebuffer() const override { return false; }
  bool present() override { return true; }

  bool resize(Size size, std::string& error) override {
    if (size == size_ && !buffer_.empty()) return true;
    std::vector<unsigned char> buffer(static_cast<size_t>(size.width) * static_cast<size_t>(size.height) * 4);
    if (!library_.make_current(context_, buffer.data(), 0x1401 /* GL_UNSIGNED_BYTE */, size.width, size.height)) {
      error =
          "osmesa: OSMesaMakeCurrent with a " + std::to_string(size.width) + "x" + std::to_string(size.height) + " buffer failed";
      return false;
    }
    buffer_ = std::move(buffer);
    size_ = size;
    return true;
  }

 private:
  OsmesaLibrary library_;
  OSMesaContext context_;
  std::vector<unsigned char> buffer_;  // the colour buffer OSMesa draws framebuffer 0 into
  Size size_;
};

}  // namespace

std::unique_ptr<Platform> create_osmesa(const Options& options, std::string& error) {
  OsmesaLibrary library;
  for (const char* soname : {"libOSMesa.so.8", "libOSMesa.so"}) {
    library.handle = dlopen(soname, RTLD_NOW | RTLD_LOCAL);
    if (library.handle) break;
  }
  if (!library.handle) {
    error = "osmesa: libOSMesa.so.8 could not be loaded (install libosmesa6)";
    return nullptr;
  }
  library.create = reinterpret_cast<CreateContextAttribs>(dlsym(library.handle, "OSMesaCreateContextAttribs"));
  library.destroy = reinterpret_cast<DestroyContext>(dlsym(library.handle, "OSMesaDestroyContext"));
  library.make_current = reinterpret_cast<MakeCurrent>(dlsym(library.handle, "OSMesaMakeCurrent"));
  library.get_proc = reinterpret_cast<GetProcAddress>(dlsym(library.handle, "OSMesaGetProcAddress"));
  if (!library.create || !library.destroy || !library.make_current || !library.get_proc) {
    error = "osmesa: libOSMesa lacks OSMesaCreateContextAttribs (Mesa 10 or later is needed)";
    return nullptr;
  }
  const int attributes[] = {kOsmesaFormat,
                            kOsmesaRgba,
                            kOsmesaDepthBits,
                            24,
                            kOsmesaStencilBits,
                            0,
                            kOsmesaAccumBits,
                            0,
                            kOsmesaProfile,
                            kOsmesaCoreProfile,
                            kOsmesaMajor,
                            4,
                            kOsmesaMinor,
                            5,
                            0};
  OSMesaContext context = library.create(attributes, nullptr);
  if (!context) {
    error = "osmesa: no OpenGL 4.5 core context (Mesa's llvmpipe provides one)";
    return nullptr;
  }
  auto platform = std::make_unique<OsmesaPlatform>(library, context);
  if (!platform->resize(options.size, error)) return nullptr;
  return platform;
}

}  // namespace platform
