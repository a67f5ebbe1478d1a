// Compressed content in glTF files: KHR_draco_mesh_compression geometry and EXT_texture_webp
// images. The test data is encoded here, with the same Debian libraries (libdraco's encoder,
// libwebp's), so no binary blobs are committed; decoding goes through the loader as a user's
// file would.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <nlohmann/json.hpp>
#include <webp/encode.h>

#include "scene/gltf/gltf_load.h"
#include "test_util.h"
#include "util/error.h"

namespace clppm {
namespace {

using json = nlohmann::json;
using test::make_temp_dir;
using test::slurp;
constexpr int kGrid = 4; // kGrid x kGrid quads on z = 0 over [0, 1]^2

struct DracoGrid {
    std::vector<char> bytes;
    int position_id = -1, normal_id = -1, uv_id = -1;
    size_t points = 0;
};

// uv = (x, 1 - y), normal +z, counter-clockwise seen from +z.
DracoGrid encode_grid(int position_bits) {
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(2 * kGrid * kGrid);
    int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    int nrm = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    int uv = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    int face = 0;
    auto add = [&](std::array<std::array<float, 2>, 3> c) {
        std::array<float, 3> p[3], n[3];
        std::array<float, 2> t[3];
        for (int k = 0; k < 3; ++k) {
            p[k] = {c[size_t(k)][0], c[size_t(k)][1], 0.f};
            n[k] = {0.f, 0.f, 1.f};
            t[k] = {c[size_t(k)][0], 1.f - c[size_t(k)][1]};
        }
        draco::FaceIndex f(uint32_t(face++));
        builder.SetAttributeValuesForFace(pos, f, p[0].data(), p[1].data(), p[2].data());
        builder.SetAttributeValuesForFace(nrm, f, n[0].data(), n[1].data(), n[2].data());
        builder.SetAttributeValuesForFace(uv, f, t[0].data(), t[1].data(), t[2].data());
    };
    const float h = 1.f / kGrid;
    for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i) {
            float x = i * h, y = j * h;
            add({{{x, y}, {x + h, y}, {x + h, y + h}}});
            add({{{x, y}, {x + h, y + h}, {x, y + h}}});
        }
    std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    draco::Encoder encoder;
    if (position_bits > 0) encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, position_bits);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
    draco::EncoderBuffer buffer;
    draco::Status status = encoder.EncodeMeshToBuffer(*mesh, &buffer);
    EXPECT_TRUE(status.ok()) << status.error_msg_string();
    DracoGrid g;
    g.bytes.assign(buffer.data(), buffer.data() + buffer.size());
    g.position_id = int(mesh->attribute(pos)->unique_id());
    g.normal_id = int(mesh->attribute(nrm)->unique_id());
    g.uv_id = int(mesh->attribute(uv)->unique_id());
    g.points = mesh->num_points();
    return g;
}

// A glTF whose one primitive is the Draco grid, its buffer in <dir>/grid.bin.
std::string write_draco_gltf(const std::string& dir, const DracoGrid& g, const std::string& name = "grid.gltf") {
    std::ofstream(dir + "/grid.bin", std::ios::binary).write(g.bytes.data(), std::streamsize(g.bytes.size()));
    json doc = {
        {"asset", {{"version", "2.0"}}},
        {"extensionsUsed", {"KHR_draco_mesh_compression"}},
        {"extensionsRequired", {"KHR_draco_mesh_compression"}},
        {"buffers", {{{"uri", "grid.bin"}, {"byteLength", g.bytes.size()}}}},
        {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", g.bytes.size()}}}},
        {"accessors",
         {{{"componentType", 5126}, {"count", g.points}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
          {{"componentType", 5126}, {"count", g.points}, {"type", "VEC3"}},
          {{"componentType", 5126}, {"count", g.points}, {"type", "VEC2"}},
          {{"componentType", 5123}, {"count", 6 * kGrid * kGrid}, {"type", "SCALAR"}}}},
        {"meshes",
         {{{"primitives",
            {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
              {"indices", 3},
              {"extensions",
               {{"KHR_draco_mesh_compression",
                 {{"bufferView", 0},
                  {"attributes",
                   {{"POSITION", g.position_id}, {"NORMAL", g.normal_id}, {"TEXCOORD_0", g.uv_id}}}}}}}}}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"scenes", {{{"nodes", {0}}}}},
        {"scene", 0}};
    std::ofstream(dir + "/" + name) << doc.dump(1);
    return dir + "/" + name;
}

// The same as a GLB container: the Draco bytes in the BIN chunk.
std::string write_draco_glb(const std::string& dir, const DracoGrid& g) {
    json doc = json::parse(slurp(write_draco_gltf(dir, g)));
    doc["buffers"][0].erase("uri");
    std::string text = doc.dump();
    while (text.size() % 4) text += ' ';
    std::vector<char> bin = g.bytes;
    while (bin.size() % 4) bin.push_back(0);
    std::string glb;
    auto u32 = [&](uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
    glb += "glTF";
    u32(2);
    u32(uint32_t(12 + 8 + text.size() + 8 + bin.size()));
    u32(uint32_t(text.size()));
    glb += "JSON";
    glb += text;
    u32(uint32_t(bin.size()));
    glb += std::string("BIN\0", 4);
    glb.append(bin.data(), bin.size());
    std::ofstream(dir + "/grid.glb", std::ios::binary) << glb;
    return dir + "/grid.glb";
}

void check_grid(const Scene& s, double position_eps) {
    ASSERT_EQ(s.num_triangles(), size_t(2 * kGrid * kGrid));
    double area = 0;
    for (size_t t = 0; t < s.num_triangles(); ++t) {
        SCOPED_TRACE("triangle " + std::to_string(t));
        const Vec3* p = &s.positions[3 * t];
        double e1[2] = {p[1].x - p[0].x, p[1].y - p[0].y}, e2[2] = {p[2].x - p[0].x, p[2].y - p[0].y};
        double cross = e1[0] * e2[1] - e1[1] * e2[0];
        EXPECT_GT(cross, 0) << "counter-clockwise seen from +z, as encoded";
        area += 0.5 * cross;
        const dev::TriShading& sh = s.shading[t];
        const float* uv[3] = {sh.uv0, sh.uv1, sh.uv2};
        const float* n[3] = {sh.n0, sh.n1, sh.n2};
        for (int k = 0; k < 3; ++k) {
            // Every vertex lies on the grid, and its attributes still belong to it.
            EXPECT_NEAR(p[k].x * kGrid, std::round(p[k].x * kGrid), position_eps * kGrid);
            EXPECT_NEAR(p[k].y * kGrid, std::round(p[k].y * kGrid), position_eps * kGrid);
            EXPECT_NEAR(p[k].z, 0, position_eps);
            EXPECT_NEAR(uv[k][0], p[k].x, 1e-3);
            EXPECT_NEAR(uv[k][1], 1 - p[k].y, 1e-3);
            EXPECT_NEAR(n[k][2], 1, 1e-3);
        }
    }
    EXPECT_NEAR(area, 1.0, 1e-3);
}

TEST(GltfDraco, CompressedGridDecodesWithItsAttributes) {
    std::string d = make_temp_dir("draco");
    Scene s = load_gltf(write_draco_gltf(d, encode_grid(0)));
    check_grid(s, 1e-6);
    for (const std::string& w : s.warnings) EXPECT_EQ(w.find("not supported"), std::string::npos) << w;
    SCOPED_TRACE("as GLB");
    check_grid(load_gltf(write_draco_glb(d, encode_grid(0))), 1e-6);
}

TEST(GltfDraco, QuantizedPositionsStayWithinTheQuantizationStep) {
    std::string d = make_temp_dir("draco_quantized");
    Scene s = load_gltf(write_draco_gltf(d, encode_grid(11)));
    check_grid(s, 1.0 / 2047);
}

std::string load_error(const std::string& path) {
    try {
        load_gltf(path);
    } catch (const Error& e) {
        return e.what();
    }
    return "(loaded)";
}

TEST(GltfDraco, DamagedDataAndUnknownAttributeIdsAreErrorsNamingThePrimitive) {
    std::string d = make_temp_dir("draco_bad");
    DracoGrid g = encode_grid(0);
    DracoGrid damaged = g;
    damaged.bytes.resize(damaged.bytes.size() / 2);
    std::string e = load_error(write_draco_gltf(d, damaged, "damaged.gltf"));
    EXPECT_NE(e.find("mesh 0 primitive 0 KHR_draco_mesh_compression: Draco data does not decode"), std::string::npos)
        << e;
    DracoGrid wrong_id = g;
    wrong_id.uv_id = 77;
    e = load_error(write_draco_gltf(d, wrong_id, "wrong_id.gltf"));
    EXPECT_NE(e.find("attribute TEXCOORD_0: no Draco attribute with id 77"), std::string::npos) << e;
    std::vector<char> junk(64, 'x');
    DracoGrid not_draco = g;
    not_draco.bytes = junk;
    e = load_error(write_draco_gltf(d, not_draco, "junk.gltf"));
    EXPECT_NE(e.find("not Draco data"), std::string::npos) << e;
}

// ---- EXT_texture_webp ----------------------------------------------------------------------------

TEST(GltfWebp, WebpTexturesDecodeLosslesslyAndTakePrecedenceOverTheFallback) {
    std::string d = make_temp_dir("webp");
    const uint8_t rgba[16] = {0, 0, 0, 255, 255, 255, 255, 255, 128, 64, 188, 255, 10, 200, 30, 128};
    uint8_t* encoded = nullptr;
    size_t size = WebPEncodeLosslessRGBA(rgba, 2, 2, 8, &encoded);
    ASSERT_GT(size, 0u);
    std::ofstream(d + "/t.webp", std::ios::binary).write(reinterpret_cast<const char*>(encoded), std::streamsize(size));
    WebPFree(encoded);
    // One triangle with uvs; the texture's `source` names a missing PNG that must not be used.
    const float tri[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
    std::ofstream(d + "/tri.bin", std::ios::binary).write(reinterpret_cast<const char*>(tri), sizeof(tri));
    json doc = {
        {"asset", {{"version", "2.0"}}},
        {"extensionsUsed", {"EXT_texture_webp"}},
        {"buffers", {{{"uri", "tri.bin"}, {"byteLength", sizeof(tri)}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
          {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}}}},
        {"accessors",
         {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
          {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}}}},
        {"images", {{{"uri", "t.webp"}}}},
        {"textures", {{{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}}}},
        {"materials", {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"material", 0}}}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"scenes", {{{"nodes", {0}}}}}};
    std::ofstream(d + "/webp.gltf") << doc.dump(1);
    Scene s = load_gltf(d + "/webp.gltf");
    ASSERT_EQ(s.textures.size(), 1u) << (s.warnings.empty() ? "" : s.warnings[0]);
    ASSERT_EQ(s.texels.size(), 4u);
    EXPECT_EQ(s.materials[0].base_color_tex, 0);
    auto srgb = [](int c) {
        double v = c / 255.0;
        return float(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
    };
    const std::array<float, 4> want[4] = {
        {0, 0, 0, 1}, {1, 1, 1, 1}, {srgb(128), srgb(64), srgb(188), 1}, {srgb(10), srgb(200), srgb(30), 128 / 255.f}};
    for (size_t t = 0; t < 4; ++t)
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(s.texels[t][size_t(c)], want[t][size_t(c)], 1e-6) << t << c;
}

} // namespace
} // namespace clppm
