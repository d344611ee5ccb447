// The volume files read back with a small reader written here, independent of the writer.
#include "ao4d/render.hpp"
#include "ao4d/shapes.hpp"
#include "helpers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

namespace ao4d {
namespace {

std::string slurp(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

std::string attribute(const std::string& xml, const std::string& tag, const std::string& name) {
    const auto t = xml.find("<" + tag);
    if (t == std::string::npos) return {};
    const auto a = xml.find(name + "=\"", t);
    const auto end = xml.find('"', a + name.size() + 2);
    return xml.substr(a + name.size() + 2, end - a - name.size() - 2);
}

struct VtiFile {
    std::vector<double> extent, origin, spacing;
    std::map<std::string, std::vector<float>> arrays;
};

std::vector<double> numbers(const std::string& s) {
    std::istringstream in(s);
    std::vector<double> v;
    for (double x; in >> x;) v.push_back(x);
    return v;
}

// Reads what ParaView needs: extent, origin, spacing and the raw appended Float32 arrays.
VtiFile read_vti(const std::filesystem::path& file) {
    const std::string data = slurp(file);
    VtiFile vti;
    EXPECT_EQ(attribute(data, "VTKFile", "type"), "ImageData");
    EXPECT_EQ(attribute(data, "VTKFile", "header_type"), "UInt64");
    vti.extent = numbers(attribute(data, "ImageData", "WholeExtent"));
    vti.origin = numbers(attribute(data, "ImageData", "Origin"));
    vti.spacing = numbers(attribute(data, "ImageData", "Spacing"));
    const auto appended = data.find("<AppendedData encoding=\"raw\">");
    const auto base = data.find('_', appended) + 1;
    for (auto pos = data.find("<DataArray"); pos < appended; pos = data.find("<DataArray", pos + 1)) {
        const std::string element = data.substr(pos, data.find('>', pos) - pos);
        EXPECT_EQ(attribute(element, "DataArray", "type"), "Float32");
        EXPECT_EQ(attribute(element, "DataArray", "format"), "appended");
        const std::size_t offset = std::stoull(attribute(element, "DataArray", "offset"));
        std::uint64_t bytes = 0;
        std::memcpy(&bytes, data.data() + base + offset, sizeof bytes);
        std::vector<float> values(bytes / sizeof(float));
        std::memcpy(values.data(), data.data() + base + offset + sizeof bytes, bytes);
        vti.arrays[attribute(element, "DataArray", "Name")] = std::move(values);
    }
    return vti;
}

void expect_same(const std::vector<float>& a, const std::vector<float>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (std::isnan(b[i])) ASSERT_TRUE(std::isnan(a[i])) << i;
        else ASSERT_EQ(a[i], b[i]) << i;
    }
}

TEST(Volume, OrthographicDepthOfAHypersphereAndItsVtiReadBack) {
    const Scene scene(make_shape("hypersphere", 8));
    CameraParams camera;
    camera.size = 9;  // odd, so the centre voxel looks at x = y = z = 0
    AoParams params;
    params.rays = 32;
    params.radius = 0.5;
    const Volume volume = render_volume(scene, camera, params);
    ASSERT_EQ(volume.ao.size(), 729u);

    // The camera's screen is at w = min_w - 0.05 * diagonal; the centre ray meets the sphere at
    // w = -1 (within the chord sag of the marched surface), a corner ray misses it.
    const double screen = scene.bounds_min().w - 0.05 * scene.diagonal();
    const std::size_t centre = 4 + 9 * (4 + 9 * 4);
    EXPECT_NEAR(volume.depth[centre], -1.0 - screen, 0.02);
    EXPECT_TRUE(std::isnan(volume.depth[0]));
    EXPECT_TRUE(std::isnan(volume.ao[0]));
    // On a convex surface nothing occludes. The marched surface is only nearly convex (linear
    // interpolation leaves shallow creases between cells), so AO is small rather than 0.
    int seen = 0;
    double sum = 0;
    for (float ao : volume.ao)
        if (!std::isnan(ao)) {
            ++seen;
            sum += ao;
        }
    EXPECT_GT(seen, 100);
    EXPECT_LT(sum / seen, 0.05);

    const auto file = std::filesystem::path(AO4D_TEST_OUTPUT_DIR) / "hypersphere.vti";
    write_vti(file, volume);
    const VtiFile vti = read_vti(file);
    EXPECT_EQ(vti.extent, (std::vector<double>{0, 8, 0, 8, 0, 8}));
    ASSERT_EQ(vti.origin.size(), 3u);
    ASSERT_EQ(vti.spacing.size(), 3u);
    for (std::size_t a = 0; a < 3; ++a) {
        EXPECT_NEAR(vti.origin[a], volume.origin[a], 1e-7);
        EXPECT_NEAR(vti.spacing[a], volume.spacing[a], 1e-7);
    }
    ASSERT_EQ(vti.arrays.size(), 2u);
    expect_same(vti.arrays.at("ao"), volume.ao);
    expect_same(vti.arrays.at("depth"), volume.depth);
}

TEST(Volume, NrrdHeaderAndDataReadBack) {
    const Scene scene(test::floor_mesh(1.0));
    CameraParams camera;
    camera.size = 4;
    camera.projection = Projection::perspective;
    AoParams params;
    params.rays = 8;
    const Volume volume = render_volume(scene, camera, params);
    // Perspective rays near the edges pass beside the plane (NaN); where it is seen it occludes nothing.
    int seen = 0;
    for (float ao : volume.ao)
        if (!std::isnan(ao)) {
            ++seen;
            EXPECT_EQ(ao, 0.0f);
        }
    EXPECT_GT(seen, 0);
    const auto file = std::filesystem::path(AO4D_TEST_OUTPUT_DIR) / "floor.nrrd";
    write_nrrd(file, volume, volume.depth);
    const std::string data = slurp(file);
    ASSERT_EQ(data.rfind("NRRD0004\n", 0), 0u);
    EXPECT_NE(data.find("\nsizes: 4 4 4\n"), std::string::npos);
    EXPECT_NE(data.find("\ntype: float\n"), std::string::npos);
    EXPECT_NE(data.find("\nendian: little\n"), std::string::npos);
    const auto body = data.find("\n\n") + 2;
    ASSERT_EQ(data.size() - body, 64 * sizeof(float));
    std::vector<float> depth(64);
    std::memcpy(depth.data(), data.data() + body, data.size() - body);
    expect_same(depth, volume.depth);
}

TEST(Volume, MontageIsWritten) {
    const Scene scene(test::floor_mesh(1.0));
    CameraParams camera;
    camera.size = 5;
    AoParams params;
    params.rays = 4;
    const auto file = std::filesystem::path(AO4D_TEST_OUTPUT_DIR) / "floor.png";
    std::filesystem::remove(file);
    write_montage(file, render_volume(scene, camera, params));
    const std::string png = slurp(file);
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png.substr(1, 3), "PNG");
}

}  // namespace
}  // namespace ao4d
