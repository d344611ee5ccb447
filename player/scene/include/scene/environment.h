#pragma once
// Image-based lighting, the CPU side: an environment (the built-in studio or an equirectangular
// image) turned once, at load, into what the shader reads: spherical harmonics for the diffuse
// share and a GGX-prefiltered cube map for the specular share (the split sum of Karis 2013, "Real
// Shading in Unreal Engine 4"), plus the split sum's BRDF table. Pure CPU: the renderer uploads it.
//
// Conventions, shared with the shader:
//
// Directions are world space, glTF's: +Y up, a default camera looking towards -Z, +X to its right.
//
// Equirectangular images (latitude-longitude, 2:1, row 0 at the top): the image is seen from
// inside, unmirrored. Its top row is +Y, its bottom row -Y; its horizontal centre looks towards -Z
// (what the default camera sees behind the model), its left and right edges towards +Z, and u
// growing to the right turns towards +X (a quarter of the width right of the centre is +X, a quarter
// left of it -X). For a unit direction d, with u, v in [0, 1] across the whole image:
//   u = 1/2 + atan2(d.x, -d.z) / (2 pi),   v = acos(d.y) / pi
//   d = (sin(v pi) sin(phi), cos(v pi), -sin(v pi) cos(phi)),   phi = (u - 1/2) 2 pi
// and pixel (i, j) of a W x H image is centred at u = (i + 1/2) / W, v = (j + 1/2) / H.
//
// Spherical harmonics: the real basis of bands 0..2 in the order of Sloan ("Stupid Spherical
// Harmonics Tricks", 2008), on the components x, y, z of the unit world direction as they are (z is
// not up here; the nine functions span the same space whichever axis is up):
//   Y0 = 0.282095                 (1 / (2 sqrt(pi)))
//   Y1 = 0.488603 y,  Y2 = 0.488603 z,  Y3 = 0.488603 x                       (sqrt(3 / (4 pi)))
//   Y4 = 1.092548 x y,  Y5 = 1.092548 y z,  Y7 = 1.092548 x z                (sqrt(15 / (4 pi)))
//   Y6 = 0.315392 (3 z^2 - 1)                                                 (sqrt(5 / (16 pi)))
//   Y8 = 0.546274 (x^2 - y^2)                                                 (sqrt(15 / (16 pi)))
//
// Cube maps: faces in GL's order +X, -X, +Y, -Y, +Z, -Z, addressed as the OpenGL ES 3.1 spec's cube
// map face table says (major axis ma; sc, tc; s = (sc / |ma| + 1) / 2, t = (tc / |ma| + 1) / 2):
//   +X: sc = -z, tc = -y    -X: sc = +z, tc = -y
//   +Y: sc = +x, tc = +z    -Y: sc = +x, tc = -z
//   +Z: sc = +x, tc = -y    -Z: sc = -x, tc = -y
// Texel (x, y) of a face of size N is centred at s = (x + 1/2) / N, t = (y + 1/2) / N; row y = 0 is
// the first row glTexImage2D uploads.
#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace scene {

// A lighting environment prepared once, at load, for image-based lighting (split sum, Karis 2013).
struct Environment {
  std::string name;  // "builtin:studio", "uniform" or the file's path
  // Diffuse: the cosine-convolved irradiance divided by pi, as the 9 coefficients (RGB) of the basis
  // above, so that a white Lambertian surface with normal n has outgoing radiance
  // sum_i irradiance_sh[i] * Y_i(n) (see diffuse_irradiance). The radiance's own projection L_i times
  // the clamped cosine's convolution factor over pi: 1 (band 0), 2/3 (band 1), 1/4 (band 2)
  // (Ramamoorthi and Hanrahan 2001: pi, 2 pi / 3, pi / 4). The mean radiance is
  // irradiance_sh[0] * 0.282095.
  std::array<glm::vec3, 9> irradiance_sh{};
  // Specular: GGX-prefiltered radiance as a cube map mip chain. specular[l] holds the 6 faces of level
  // l (size face_size >> l) for perceptual roughness l / (levels() - 1) (alpha = roughness^2): level 0
  // is the environment itself. Each face is face_size >> l rows of RGB floats, linear radiance, laid
  // out as the cube map table above says.
  int face_size = 0;
  std::vector<std::vector<float>> specular;  // [level][face * size * size * 3 + (y * size + x) * 3 + c]
  int levels() const { return static_cast<int>(specular.size()); }
};

// The built-in neutral studio (what the player lights with when nothing else is given): a grey
// surround brighter above than below, with two broad soft boxes above, white (no tint), made
// procedurally (no asset file). Its mean radiance is about 0.55; a white diffuse surface facing up
// reads about 0.8 and one facing down about 0.35 (the studio replaces the ambient share of the
// player's former look: 0.35 plus a directional key light).
const Environment& studio_environment();  // prepared once, on first use (thread-safe); cheap after

// A uniform environment of constant radiance (white furnace tests): every direction `radiance`.
// Prepared the way an image is, so the tests that use it check the prefiltering's normalization.
Environment uniform_environment(glm::vec3 radiance, int face_size = 32);

// The limits of load_environment, checked before any pixel is decoded.
inline constexpr int kEnvironmentMaxWidth = 16384;
inline constexpr std::size_t kEnvironmentMaxFileBytes = std::size_t(512) << 20;
inline constexpr std::size_t kEnvironmentDecodedBudget = std::size_t(512) << 20;  // the image as RGB floats

// An equirectangular image (latitude-longitude, 2:1; see the conventions above): HDR (Radiance),
// OpenEXR or any other format OpenImageIO reads, RGB or RGBA (alpha is ignored). Floating-point
// pixels are linear radiance; integer pixels (8- or 16-bit) are taken as sRGB-encoded. The file is
// read through base::read_regular_file (a FIFO or device is refused unread; at most
// kEnvironmentMaxFileBytes) and decoded from memory. Refused before decoding: a size not 2:1 within
// a pixel of height, wider than kEnvironmentMaxWidth, or more than kEnvironmentDecodedBudget decoded;
// after decoding and before preparing: a non-finite or negative value (the pixel is named). False
// and why in `error`, "PATH: what; expected ...".
bool load_environment(const std::filesystem::path& file, Environment& out, std::string& error);

// Prepares an Environment from an equirectangular image in memory: width x height RGB floats, row 0
// at the top, linear, finite and non-negative. face_size is a power of two; levels is at least 1
// and at most log2(face_size) + 1. Throws std::invalid_argument when they are not (a caller's bug:
// load_environment checks what a file can get wrong). Used by load_environment, the studio and tests.
// Once keep_prepared_environments() has named a folder, what it prepares is kept there and read back
// instead of prepared again, by the same build of the player for the same pixels and sizes.
Environment prepare_environment(std::string name, int width, int height, const std::vector<float>& rgb, int face_size = 128,
                                int levels = 6);

// Prepared environments kept between runs: the prefiltering takes seconds on a board (65 s under
// ASan in the test VM), which every start paid before its first scene frame. Call once at start,
// before anything is prepared (the player does, in its shader cache folder); empty keeps none. Each
// file names the build that wrote it (its GNU build id: a build without one keeps nothing), so an
// upgrade never reads an older build's result; a damaged or truncated file is removed and the
// environment prepared again. Naming the folder prunes it, least recently used first.
inline constexpr std::size_t kMaxKeptEnvironments = 32;  // one is 1.6 MB at face 128
inline constexpr std::uintmax_t kMaxKeptEnvironmentBytes = std::uintmax_t(64) << 20;
void keep_prepared_environments(const std::filesystem::path& dir);

struct EnvironmentCacheCounts {
  std::size_t prepared = 0, loaded = 0, rejected = 0;  // rejected: damaged files, prepared again
  std::filesystem::path dir;                           // empty: none kept
  std::string problem;                                 // the last failure to keep one, if any
};
EnvironmentCacheCounts environment_cache_counts();

// The split-sum BRDF table (Karis 2013): size x size entries (A, B), F0 * A + B being the directional
// albedo of GGX with height-correlated Smith visibility and Schlick's Fresnel, for
// n.v = (x + 0.5) / size and perceptual roughness (y + 0.5) / size, integrated by importance sampling
// `samples` Hammersley points. Row-major, y outer.
std::vector<glm::vec2> split_sum_lut(int size = 32, int samples = 512);

// The shader's evaluations, on the CPU (for tests and the CPU reference):
// the basis above at the unit direction n;
std::array<float, 9> sh_basis(glm::vec3 n);
// the radiance a white Lambertian surface with normal n reflects: sum_i irradiance_sh[i] Y_i(n),
// clamped at 0 (band-2 ringing around a bright, small light can dip below it);
glm::vec3 diffuse_irradiance(const Environment& env, glm::vec3 normal);
// the prefiltered radiance towards `direction` (any length) at perceptual roughness in [0, 1]:
// bilinear within a face (clamped at its edges), linear between the two levels around
// roughness * (levels() - 1), as textureLod does;
glm::vec3 sample_specular(const Environment& env, glm::vec3 direction, float roughness);

// The cube map table above: the face and (s, t) a direction (any length, not zero) reads, and back,
// the unit direction through (s, t) of a face.
struct CubeCoord {
  int face = 0;
  float s = 0.5f, t = 0.5f;
};
CubeCoord cube_coord(glm::vec3 direction);
glm::vec3 cube_direction(int face, float s, float t);

// The equirectangular mapping above: (u, v) of a unit direction, and the unit direction of (u, v).
glm::vec2 equirect_uv(glm::vec3 direction);
glm::vec3 equirect_direction(float u, float v);

}  // namespace scene
