// Small readers for the volume files ao4d writes, written here independently of the writers, shared
// by the library tests (output_test.cpp) and the command's end-to-end tests (cli_test.cpp).
#pragma once

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace ao4d::test {

inline std::string slurp(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

inline std::string attribute(const std::string& xml, const std::string& tag, const std::string& name) {
    const auto t = xml.find("<" + tag);
    if (t == std::string::npos) return {};
    const auto a = xml.find(name + "=\"", t);
    if (a == std::string::npos) return {};
    const auto end = xml.find('"', a + name.size() + 2);
    return xml.substr(a + name.size() + 2, end - a - name.size() - 2);
}

// Whitespace-separated numbers; with `separators`, those characters count as whitespace too.
inline std::vector<double> numbers(std::string s, const std::string& separators = {}) {
    for (char& c : s)
        if (separators.find(c) != std::string::npos) c = ' ';
    std::istringstream in(s);
    std::vector<double> v;
    for (double x; in >> x;) v.push_back(x);
    return v;
}

struct VtiFile {
    std::vector<double> extent, origin, spacing;
    std::map<std::string, std::vector<float>> arrays;
};

// The grid a .vti file declares matches the volume written: extent 0..last on each axis, origin, spacing.
template <class Volume>
void expect_vti_grid(const VtiFile& vti, double last, const Volume& volume) {
    EXPECT_EQ(vti.extent, (std::vector<double>{0, last, 0, last, 0, last}));
    ASSERT_EQ(vti.origin.size(), 3u);
    ASSERT_EQ(vti.spacing.size(), 3u);
    for (std::size_t a = 0; a < 3; ++a) {
        EXPECT_NEAR(vti.origin[a], volume.origin[a], 1e-7);
        EXPECT_NEAR(vti.spacing[a], volume.spacing[a], 1e-7);
    }
}

// Reads what ParaView needs: extent, origin, spacing and the raw appended Float32 arrays.
inline VtiFile read_vti(const std::filesystem::path& file) {
    const std::string data = slurp(file);
    VtiFile vti;
    EXPECT_EQ(attribute(data, "VTKFile", "type"), "ImageData") << file;
    EXPECT_EQ(attribute(data, "VTKFile", "header_type"), "UInt64") << file;
    vti.extent = numbers(attribute(data, "ImageData", "WholeExtent"));
    vti.origin = numbers(attribute(data, "ImageData", "Origin"));
    vti.spacing = numbers(attribute(data, "ImageData", "Spacing"));
    const auto appended = data.find("<AppendedData encoding=\"raw\">");
    if (appended == std::string::npos) {
        ADD_FAILURE() << file << ": no raw appended data";
        return vti;
    }
    const auto base = data.find('_', appended) + 1;
    for (auto pos = data.find("<DataArray"); pos < appended; pos = data.find("<DataArray", pos + 1)) {
        const std::string element = data.substr(pos, data.find('>', pos) - pos);
        EXPECT_EQ(attribute(element, "DataArray", "type"), "Float32");
        EXPECT_EQ(attribute(element, "DataArray", "format"), "appended");
        const std::size_t offset = std::stoull(attribute(element, "DataArray", "offset"));
        std::uint64_t bytes = 0;
        if (base + offset + sizeof bytes > data.size()) {
            ADD_FAILURE() << file << ": array offset beyond the end of the file";
            return vti;
        }
        std::memcpy(&bytes, data.data() + base + offset, sizeof bytes);
        if (base + offset + sizeof bytes + bytes > data.size()) {
            ADD_FAILURE() << file << ": array data beyond the end of the file";
            return vti;
        }
        std::vector<float> values(bytes / sizeof(float));
        std::memcpy(values.data(), data.data() + base + offset + sizeof bytes, bytes);
        vti.arrays[attribute(element, "DataArray", "Name")] = std::move(values);
    }
    return vti;
}

struct NrrdFile {
    std::string magic;
    std::map<std::string, std::string> fields;  // "key: value" lines; comments skipped
    std::vector<float> data;                    // the raw little-endian floats after the blank line
};

inline NrrdFile read_nrrd(const std::filesystem::path& file) {
    const std::string text = slurp(file);
    NrrdFile nrrd;
    const auto body = text.find("\n\n");
    if (body == std::string::npos) {
        ADD_FAILURE() << file << ": no blank line ends the header";
        return nrrd;
    }
    std::istringstream header(text.substr(0, body));
    std::getline(header, nrrd.magic);
    for (std::string line; std::getline(header, line);) {
        if (line.empty() || line[0] == '#') continue;
        const auto colon = line.find(": ");
        if (colon == std::string::npos) {
            ADD_FAILURE() << file << ": header line without 'key: value': " << line;
            continue;
        }
        nrrd.fields[line.substr(0, colon)] = line.substr(colon + 2);
    }
    const std::size_t bytes = text.size() - body - 2;
    EXPECT_EQ(bytes % sizeof(float), 0u) << file;
    nrrd.data.resize(bytes / sizeof(float));
    std::memcpy(nrrd.data.data(), text.data() + body + 2, nrrd.data.size() * sizeof(float));
    return nrrd;
}

struct Image {
    int width = 0, height = 0, channels = 0;
    std::vector<std::uint8_t> pixels;  // rows top to bottom, channels interleaved
    std::array<int, 3> rgb(int x, int y) const {
        const std::size_t p = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) *
                              static_cast<std::size_t>(channels);
        return {pixels[p], pixels[p + 1], pixels[p + 2]};
    }
};

// Through OpenImageIO, as 8-bit channels; an empty image (and a test failure) if it cannot be read.
inline Image read_image(const std::filesystem::path& file) {
    Image image;
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) {
        ADD_FAILURE() << file << ": cannot open (" << OIIO::geterror() << ")";
        return image;
    }
    const OIIO::ImageSpec& spec = in->spec();
    image.width = spec.width;
    image.height = spec.height;
    image.channels = spec.nchannels;
    image.pixels.resize(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) *
                        static_cast<std::size_t>(spec.nchannels));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, image.pixels.data())) {
        ADD_FAILURE() << file << ": cannot read (" << in->geterror() << ")";
        image = {};
    }
    in->close();
    return image;
}

// The montage's layout (write_montage): z slices in rows of ceil(sqrt(nz)) slices, each framed by
// 2 grey (96) pixels, y up within a slice; voxel brightness 255 (1 - AO), misses dark blue.
inline void expect_montage_shows(const Image& png, const std::array<int, 3>& dims, const std::vector<float>& ao) {
    const int nx = dims[0], ny = dims[1], nz = dims[2];
    int cols = 1;
    while (cols * cols < nz) ++cols;
    const int rows = (nz + cols - 1) / cols;
    ASSERT_EQ(png.width, cols * (nx + 2) + 2);
    ASSERT_EQ(png.height, rows * (ny + 2) + 2);
    ASSERT_EQ(png.channels, 3);
    ASSERT_EQ(ao.size(), static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz));
    std::vector<bool> voxel_pixel(static_cast<std::size_t>(png.width) * static_cast<std::size_t>(png.height), false);
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const int x = 2 + (k % cols) * (nx + 2) + i, y = 2 + (k / cols) * (ny + 2) + (ny - 1 - j);
                voxel_pixel[static_cast<std::size_t>(y * png.width + x)] = true;
                const float a = ao[static_cast<std::size_t>(i + nx * (j + ny * k))];
                const int v = std::isnan(a) ? 0 : static_cast<int>(std::lround(255.0 * (1.0 - a)));
                const std::array<int, 3> expected = std::isnan(a) ? std::array<int, 3>{16, 24, 64} : std::array<int, 3>{v, v, v};
                ASSERT_EQ(png.rgb(x, y), expected) << "voxel " << i << ' ' << j << ' ' << k;
            }
    for (int y = 0; y < png.height; ++y)
        for (int x = 0; x < png.width; ++x)
            if (!voxel_pixel[static_cast<std::size_t>(y * png.width + x)]) {
                ASSERT_EQ(png.rgb(x, y), (std::array<int, 3>{96, 96, 96})) << "pixel " << x << ' ' << y;
            }
}

}  // namespace ao4d::test
