// A 4D camera that projects a scene onto a 3D image volume, and the volume's file formats.
#pragma once

#include "ao4d/scene.hpp"

#include <array>
#include <filesystem>
#include <vector>

namespace ao4d {

enum class Projection { orthographic, perspective };

// The camera looks along +w. Its image is a cube of `size`^3 voxels covering the scene's x, y, z
// bounds (with a margin); orthographic rays are parallel to w, perspective rays leave an eye
// placed `eye_distance` scene diagonals in front of the image so that nearer parts look larger.
struct CameraParams {
    Projection projection = Projection::orthographic;
    int size = 50;
    double eye_distance = 1.5;
};

// Point data on a regular grid, x fastest. Voxels whose ray misses hold NaN in both arrays.
struct Volume {
    std::array<int, 3> dims{};
    std::array<double, 3> origin{}, spacing{};
    std::vector<float> ao;     // AO of the first hit
    std::vector<float> depth;  // distance along the ray to the first hit
};

// Voxel i is seeded with point_seed(ao.seed, SeedStream::voxels, i), so the volume is the same for
// any thread count.
Volume render_volume(const Scene& scene, const CameraParams& camera, const AoParams& ao, const ProgressFn& progress = {});

// VTK XML ImageData with "ao" and "depth" point arrays (raw appended Float32), which ParaView
// opens as is. Throws naming the file on failure.
void write_vti(const std::filesystem::path& file, const Volume& volume);
// NRRD (raw little-endian float, with space origin and directions) of one array.
void write_nrrd(const std::filesystem::path& file, const Volume& volume, const std::vector<float>& values);
// All z slices side by side in a grid, brightness 1 - AO, misses dark blue, through OpenImageIO.
void write_montage(const std::filesystem::path& file, const Volume& volume);

}  // namespace ao4d
