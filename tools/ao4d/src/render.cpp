#include "ao4d/render.hpp"

#include "ao4d/sampling.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace ao4d {

static_assert(std::endian::native == std::endian::little, "the .vti and .nrrd writers declare little-endian data");

Volume render_volume(const Scene& scene, const CameraParams& camera, const AoParams& ao, const ProgressFn& progress) {
  if (camera.size < 1) throw std::invalid_argument("volume size must be at least 1");
  const int n = camera.size;
  const Vec4 lo = scene.bounds_min(), hi = scene.bounds_max();
  const double diagonal = std::max(scene.diagonal(), 1e-12);
  // A cube around the x, y, z bounds with a 5% margin, so every voxel is a cube too.
  double half = 0;
  for (std::size_t a = 0; a < 3; ++a) half = std::max(half, 0.5 * (hi[a] - lo[a]));
  half = half * 1.05 + 1e-12;
  const double step = n > 1 ? 2.0 * half / (n - 1) : 0.0;
  Volume volume;
  volume.dims = {n, n, n};
  for (std::size_t a = 0; a < 3; ++a) {
    volume.origin[a] = 0.5 * (lo[a] + hi[a]) - (n > 1 ? half : 0.0);
    volume.spacing[a] = n > 1 ? step : 1.0;
  }
  const double screen_w = lo.w - 0.05 * diagonal;
  const Vec4 eye{0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y), 0.5 * (lo.z + hi.z), screen_w - camera.eye_distance * diagonal};
  const double t_max = 4.0 * diagonal;  // far beyond the scene from anywhere on the screen

  const std::size_t count = static_cast<std::size_t>(n) * n * n;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  volume.ao.assign(count, nan);
  volume.depth.assign(count, nan);
  parallel_for(
      count, ao.threads,
      [&](std::size_t voxel) {
        const std::size_t i = voxel % n, j = (voxel / n) % n, k = voxel / (static_cast<std::size_t>(n) * n);
        const Vec4 origin{volume.origin[0] + static_cast<double>(i) * step, volume.origin[1] + static_cast<double>(j) * step,
                          volume.origin[2] + static_cast<double>(k) * step, screen_w};
        const Vec4 dir = camera.projection == Projection::orthographic ? Vec4{0, 0, 0, 1} : normalize(origin - eye);
        const auto hit = scene.closest_hit(origin, dir, 0.0, t_max);
        if (!hit) return;
        Vec4 normal = scene.normal(hit->cell);
        if (dot(normal, dir) > 0) normal = -normal;  // AO of the side the camera sees
        const Vec4 p = origin + hit->t * dir;
        volume.ao[voxel] = static_cast<float>(
            ambient_occlusion(scene, p, normal, ao, point_seed(ao.seed, SeedStream::voxels, voxel), hit->cell));
        volume.depth[voxel] = static_cast<float>(hit->t);
      },
      progress);
  return volume;
}

namespace {

std::ofstream open_output(const std::filesystem::path& file) {
  std::ofstream out(file, std::ios::binary);
  if (!out) throw std::runtime_error(file.string() + ": cannot open for writing");
  out << std::setprecision(9);
  return out;
}

void finish(std::ofstream& out, const std::filesystem::path& file) {
  out.close();
  if (!out) throw std::runtime_error(file.string() + ": write failed");
}

void check_volume(const Volume& volume, const std::vector<float>& values, const std::filesystem::path& file) {
  const std::size_t count = static_cast<std::size_t>(volume.dims[0]) * volume.dims[1] * volume.dims[2];
  if (values.size() != count)
    throw std::invalid_argument(file.string() + ": volume array has " + std::to_string(values.size()) + " values, expected " +
                                std::to_string(count));
}

void write_raw_array(std::ofstream& out, const std::vector<float>& values) {
  const std::uint64_t bytes = values.size() * sizeof(float);
  out.write(reinterpret_cast<const char*>(&bytes), sizeof bytes);
  out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(bytes));
}

}  // namespace

void write_vti(const std::filesystem::path& file, const Volume& volume) {
  check_volume(volume, volume.ao, file);
  check_volume(volume, volume.depth, file);
  auto out = open_output(file);
  const auto& d = volume.dims;
  std::ostringstream extent;
  extent << "0 " << d[0] - 1 << " 0 " << d[1] - 1 << " 0 " << d[2] - 1;
  const std::uint64_t block = sizeof(std::uint64_t) + volume.ao.size() * sizeof(float);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      << "  <ImageData WholeExtent=\"" << extent.str() << "\" Origin=\"" << volume.origin[0] << ' ' << volume.origin[1] << ' '
      << volume.origin[2] << "\" Spacing=\"" << volume.spacing[0] << ' ' << volume.spacing[1] << ' ' << volume.spacing[2]
      << "\">\n"
      << "    <Piece Extent=\"" << extent.str() << "\">\n"
      << "      <PointData Scalars=\"ao\">\n"
      << "        <DataArray type=\"Float32\" Name=\"ao\" format=\"appended\" offset=\"0\"/>\n"
      << "        <DataArray type=\"Float32\" Name=\"depth\" format=\"appended\" offset=\"" << block << "\"/>\n"
      << "      </PointData>\n"
      << "    </Piece>\n"
      << "  </ImageData>\n"
      << "  <AppendedData encoding=\"raw\">\n_";
  write_raw_array(out, volume.ao);
  write_raw_array(out, volume.depth);
  out << "\n  </AppendedData>\n</VTKFile>\n";
  finish(out, file);
}

void write_nrrd(const std::filesystem::path& file, const Volume& volume, const std::vector<float>& values) {
  check_volume(volume, values, file);
  auto out = open_output(file);
  const auto& s = volume.spacing;
  out << "NRRD0004\n"
      << "# ao4d volume, NaN where the camera ray hits nothing\n"
      << "type: float\n"
      << "dimension: 3\n"
      << "space dimension: 3\n"
      << "sizes: " << volume.dims[0] << ' ' << volume.dims[1] << ' ' << volume.dims[2] << '\n'
      << "space directions: (" << s[0] << ",0,0) (0," << s[1] << ",0) (0,0," << s[2] << ")\n"
      << "space origin: (" << volume.origin[0] << ',' << volume.origin[1] << ',' << volume.origin[2] << ")\n"
      << "endian: little\n"
      << "encoding: raw\n\n";
  out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(float)));
  finish(out, file);
}

void write_montage(const std::filesystem::path& file, const Volume& volume) {
  check_volume(volume, volume.ao, file);
  const int nx = volume.dims[0], ny = volume.dims[1], nz = volume.dims[2];
  const int cols = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(nz))));
  const int rows = (nz + cols - 1) / cols;
  constexpr int kGap = 2;
  const int width = cols * (nx + kGap) + kGap, height = rows * (ny + kGap) + kGap;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3, 96);  // grey gaps
  for (int k = 0; k < nz; ++k) {
    const int x0 = kGap + (k % cols) * (nx + kGap), y0 = kGap + (k / cols) * (ny + kGap);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const float ao =
            volume.ao[static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k)];
        // Image rows go down, y goes up.
        const std::size_t px = (static_cast<std::size_t>(y0 + ny - 1 - j) * width + static_cast<std::size_t>(x0 + i)) * 3;
        if (std::isnan(ao)) {
          rgb[px] = 16, rgb[px + 1] = 24, rgb[px + 2] = 64;
        } else {
          const auto v = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(1.0 - ao, 0.0, 1.0)));
          rgb[px] = rgb[px + 1] = rgb[px + 2] = v;
        }
      }
  }
  const std::string name = file.string();
  auto out = OIIO::ImageOutput::create(name);
  if (!out) throw std::runtime_error(name + ": cannot create an image writer (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  if (!out->open(name, spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgb.data()) || !out->close())
    throw std::runtime_error(name + ": cannot write the montage (" + out->geterror() + ")");
}

}  // namespace ao4d
