#include "platform/backends.h"

#include "gl/gl_api.h"

#include <dlfcn.h>

#include <vector>

namespace platform {
namespace {

// From GL/osmesa.h, which cannot be included beside the GLES headers. OSMesa is opened with
// dlopen(RTLD_LOCAL) so its gl* exports never clash with libGLESv2's.
using OSMesaContext = void*;
constexpr int kOsmesaRgba = 0x1908;  // GL_RGBA
constexpr int kOsmesaFormat = 0x22, kOsmesaDepthBits = 0x30, kOsmesaStencilBits = 0x31,
              kOsmesaAccumBits = 0x32, kOsmesaProfile = 0x33, kOsmesaCoreProfile = 0x34,
              kOsmesaMajor = 0x36, kOsmesaMinor = 0x37;
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

void* osmesa_proc(const char* name, void* user) {
  return static_cast<OsmesaLibrary*>(user)->get_proc(name);
}

class OsmesaPlatform final : public Platform {
 public:
  OsmesaPlatform(OsmesaLibrary library, OSMesaContext context, std::vector<unsigned char> buffer)
      : library_(library), context_(context), buffer_(std::move(buffer)) {}
  ~OsmesaPlatform() override {
    library_.destroy(context_);
    // The library stays loaded: Mesa's atexit handlers still point into it.
  }
  std::string_view name() const override { return "osmesa"; }
  std::string description() const override { return "OSMesa, desktop OpenGL 4.5 core profile"; }
  std::vector<std::string> extensions_used() const override { return {"OSMesaCreateContextAttribs"}; }

 private:
  OsmesaLibrary library_;
  OSMesaContext context_;
  std::vector<unsigned char> buffer_;  // OSMesa needs a colour buffer to make a context current
};

}  // namespace

std::unique_ptr<Platform> create_osmesa(bool, std::string& error) {
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
  const int attributes[] = {kOsmesaFormat, kOsmesaRgba, kOsmesaDepthBits, 24, kOsmesaStencilBits, 0,
                            kOsmesaAccumBits, 0, kOsmesaProfile, kOsmesaCoreProfile,
                            kOsmesaMajor, 4, kOsmesaMinor, 5, 0};
  OSMesaContext context = library.create(attributes, nullptr);
  if (!context) {
    error = "osmesa: no OpenGL 4.5 core context (Mesa's llvmpipe provides one)";
    return nullptr;
  }
  constexpr int kSide = 16;
  std::vector<unsigned char> buffer(kSide * kSide * 4);
  if (!library.make_current(context, buffer.data(), 0x1401 /* GL_UNSIGNED_BYTE */, kSide, kSide)) {
    library.destroy(context);
    error = "osmesa: OSMesaMakeCurrent failed";
    return nullptr;
  }
  std::string load_error;
  if (!gl::load(osmesa_proc, &library, load_error)) {
    library.destroy(context);
    error = "osmesa: " + load_error;
    return nullptr;
  }
  return std::make_unique<OsmesaPlatform>(library, context, std::move(buffer));
}

}  // namespace platform
