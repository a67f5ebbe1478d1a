// The glTF loader against the small files of tests/data (written by tests/data/make_test_gltf.py,
// which documents the geometry behind every expected number) and the shipped scenes.
#include "scene/gltf/gltf_load.h"
#include "scene/light_power.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <nlohmann/json.hpp>

#include "test_util.h"
#include "util/error.h"

namespace clppm {
namespace {

const double kPi = 3.14159265358979323846;

std::string data(const std::string& name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }
std::string scene_file(const std::string& name) { return std::string(CLPPM_SCENES_DIR) + "/" + name; }

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void expect_vec3(const float* v, double x, double y, double z, double eps = 1e-5) {
    EXPECT_NEAR(v[0], x, eps);
    EXPECT_NEAR(v[1], y, eps);
    EXPECT_NEAR(v[2], z, eps);
}

void expect_pos(const Scene& s, size_t tri, int k, double x, double y, double z, double eps = 1e-5) {
    const Vec3& p = s.positions[3 * tri + size_t(k)];
    SCOPED_TRACE("triangle " + std::to_string(tri) + " vertex " + std::to_string(k));
    EXPECT_NEAR(p.x, x, eps);
    EXPECT_NEAR(p.y, y, eps);
    EXPECT_NEAR(p.z, z, eps);
}

// Unit normal of the stored winding: (p1 - p0) x (p2 - p0).
std::array<double, 3> winding_normal(const Scene& s, size_t tri) {
    const Vec3* p = &s.positions[3 * tri];
    double e1[3] = {p[1].x - p[0].x, p[1].y - p[0].y, p[1].z - p[0].z};
    double e2[3] = {p[2].x - p[0].x, p[2].y - p[0].y, p[2].z - p[0].z};
    std::array<double, 3> c = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                               e1[0] * e2[1] - e1[1] * e2[0]};
    double len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    return {c[0] / len, c[1] / len, c[2] / len};
}

bool has_warning(const Scene& s, const std::string& key) {
    for (const std::string& w : s.warnings)
        if (w.find(key) != std::string::npos) return true;
    return false;
}

std::string load_error(const std::string& path) {
    try {
        load_gltf(path);
    } catch (const Error& e) {
        return e.what();
    }
    ADD_FAILURE() << path << " loaded without an error";
    return "";
}

// The message names the file first, holds `key`, and is one line.
void expect_error(const std::string& name, const std::string& key) {
    std::string path = data(name);
    std::string msg = load_error(path);
    EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
    EXPECT_NE(msg.find(key), std::string::npos) << "expected '" << key << "' in: " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

float srgb(int c) {
    double v = c / 255.0;
    return float(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
}

// ---- geometry -----------------------------------------------------------------------------------

TEST(GltfHierarchy, TrsParentMatrixChildInTheDefaultScene) {
    Scene s = load_gltf(data("hierarchy.gltf"));
    // "scene": 1 holds parent and squashed; scene 0 would give one triangle.
    ASSERT_EQ(s.num_triangles(), 2u);
    ASSERT_EQ(s.positions.size(), 6u);
    // child = T(1,2,3) Rz(90 deg) S(2) * T(0,0,1) applied to (0,0,0), (1,0,0), (0,1,0).
    expect_pos(s, 0, 0, 1, 2, 5);
    expect_pos(s, 0, 1, 1, 4, 5);
    expect_pos(s, 0, 2, -1, 2, 5);
    expect_vec3(s.shading[0].n0, 0, 0, 1);
    expect_vec3(s.shading[0].n2, 0, 0, 1);
    EXPECT_TRUE(s.cameras.empty());
    EXPECT_TRUE(s.punctual_lights.empty());
    EXPECT_EQ(s.source, data("hierarchy.gltf"));
}

TEST(GltfHierarchy, NonUniformScaleTransformsNormalsByInverseTranspose) {
    Scene s = load_gltf(data("hierarchy.gltf"));
    ASSERT_EQ(s.num_triangles(), 2u);
    expect_pos(s, 1, 0, 10, 0, 0);
    expect_pos(s, 1, 1, 11, 0, 0);
    expect_pos(s, 1, 2, 10, 4, 1);
    // (0,-1,1)/sqrt2 through diag(1,4,1)^-T = (0,-1,4)/sqrt17: still perpendicular to the surface.
    double r = std::sqrt(17.0);
    expect_vec3(s.shading[1].n0, 0, -1 / r, 4 / r);
    std::array<double, 3> g = winding_normal(s, 1);
    expect_vec3(s.shading[1].n1, g[0], g[1], g[2]);
}

TEST(GltfIndices, U8U16U32AndNonIndexedGiveTheSameQuads) {
    Scene s = load_gltf(data("index_types.gltf"));
    ASSERT_EQ(s.num_triangles(), 8u);
    for (int q = 0; q < 4; ++q) {
        SCOPED_TRACE("quad " + std::to_string(q));
        size_t t = size_t(2 * q);
        expect_pos(s, t, 0, 0, 0, q);
        expect_pos(s, t, 1, 1, 0, q);
        expect_pos(s, t, 2, 1, 1, q);
        expect_pos(s, t + 1, 0, 0, 0, q);
        expect_pos(s, t + 1, 1, 1, 1, q);
        expect_pos(s, t + 1, 2, 0, 1, q);
    }
    EXPECT_EQ(s.degenerate_triangles_skipped, 0u);
    EXPECT_EQ(s.meshes_without_normals, 0u);
}

TEST(GltfAccessors, ByteStrideAndNormalizedTexcoords) {
    Scene s = load_gltf(data("byte_stride.gltf"));
    ASSERT_EQ(s.num_triangles(), 2u);
    expect_pos(s, 0, 1, 1, 0, 0);
    expect_pos(s, 0, 2, 0, 1, 0);
    expect_vec3(s.shading[0].n1, 0, 0, 1);
    // u16 normalized (32768, 65535) -> (32768/65535, 1).
    EXPECT_FLOAT_EQ(s.shading[0].uv0[0], 0.f);
    EXPECT_FLOAT_EQ(s.shading[0].uv1[0], 1.f);
    EXPECT_NEAR(s.shading[0].uv2[0], 32768.0 / 65535.0, 1e-6);
    EXPECT_FLOAT_EQ(s.shading[0].uv2[1], 1.f);
    // u8 normalized (0,255), (51,0), (255,102) -> (0,1), (0.2,0), (1,0.4).
    EXPECT_FLOAT_EQ(s.shading[1].uv0[1], 1.f);
    EXPECT_NEAR(s.shading[1].uv1[0], 0.2, 1e-6);
    EXPECT_NEAR(s.shading[1].uv2[1], 0.4, 1e-6);
}

// KHR_mesh_quantization: integer positions are dequantized by the node transform, normalized
// integers map as glTF 2.0 Sec. 3.11 says, unnormalized texcoords keep their integer values.
TEST(GltfAccessors, QuantizedAttributesDecodeExactly) {
    Scene s = load_gltf(data("quantized.gltf"));
    ASSERT_EQ(s.num_triangles(), 3u);
    expect_pos(s, 0, 1, 1, 0, 0); // SHORT (100, 0, 0) * 0.01
    expect_pos(s, 0, 2, 1, 2, 0);
    expect_pos(s, 1, 2, 0, 2, 0);
    expect_vec3(s.shading[0].n0, 0, 0, 1); // normalized BYTE (0, 0, 127)
    EXPECT_FLOAT_EQ(s.shading[0].uv1[0], 1.f);
    EXPECT_FLOAT_EQ(s.shading[0].uv2[1], -1.f); // normalized SHORT -32767
    expect_pos(s, 2, 1, 1, 0, 1);               // normalized UNSIGNED_BYTE 255
    expect_pos(s, 2, 2, 0, 0.2, 1);             // 51 / 255
    EXPECT_FLOAT_EQ(s.shading[2].uv1[0], 2.f);  // unnormalized UNSIGNED_BYTE
    EXPECT_FLOAT_EQ(s.shading[2].uv2[1], 3.f);
    EXPECT_FALSE(has_warning(s, "not supported")) << "the required extension is read, not ignored";
}

TEST(GltfAccessors, SparseSubstitutionsAndAccessorsWithoutABufferView) {
    Scene s = load_gltf(data("sparse.gltf"));
    ASSERT_EQ(s.num_triangles(), 2u);
    expect_pos(s, 0, 0, 0, 0, 0);
    expect_pos(s, 0, 1, 2, 0, 0); // sparse value replaces (1, 0, 0)
    expect_pos(s, 0, 2, 0, 1, 0);
    expect_pos(s, 1, 0, 0, 0, 0); // no bufferView: zeros
    expect_pos(s, 1, 1, 1, 0, 5);
    expect_pos(s, 1, 2, 0, 1, 5);
}

TEST(GltfErrors, SparseIndicesOutOfOrderOrRangeAreRefused) {
    expect_error("sparse_unsorted.gltf", "accessor 1 sparse indices are not strictly increasing");
    expect_error("sparse_index_range.gltf", "accessor 1 sparse index 7 is beyond its 3 elements");
}

// glTF 2.0 Sec. 3.7.2.1: strip p_i = {v_i, v_{i+1+i%2}, v_{i+2-i%2}}, fan p_i = {v_{i+1}, v_{i+2}, v_0}.
TEST(GltfIndices, StripsAndFansAreTriangulatedAsTheSpecificationSays) {
    Scene s = load_gltf(data("strips_fans.gltf"));
    ASSERT_EQ(s.num_triangles(), 10u) << "3 strip + 3 fan + 4 joined-strip triangles";
    // Strip (0,1) (0,0) (1,1) (1,0) (2,1): the second triangle is {v1, v3, v2}.
    expect_pos(s, 1, 0, 0, 0, 0);
    expect_pos(s, 1, 1, 1, 0, 0);
    expect_pos(s, 1, 2, 1, 1, 0);
    // Fan: the first triangle is {v1, v2, v0}.
    expect_pos(s, 3, 0, 1, 0, 1);
    expect_pos(s, 3, 1, 1, 1, 1);
    expect_pos(s, 3, 2, 0, 0, 1);
    // The joined strip's second quad starts at x = 5.
    expect_pos(s, 8, 0, 5, 1, 2);
    for (size_t t = 0; t < s.num_triangles(); ++t) {
        SCOPED_TRACE("triangle " + std::to_string(t));
        std::array<double, 3> g = winding_normal(s, t);
        EXPECT_NEAR(g[2], 1.0, 1e-6) << "every assembled triangle keeps the counter-clockwise front face";
    }
    EXPECT_EQ(s.degenerate_triangles_skipped, 0u) << "strip joints are intended, not degenerate input";
}

TEST(GltfHierarchy, GpuInstancingDrawsTheMeshAtEachInstanceTransform) {
    Scene s = load_gltf(data("gpu_instancing.gltf"));
    ASSERT_EQ(s.num_triangles(), 3u);
    expect_pos(s, 0, 1, 1, 0, 10);
    expect_pos(s, 1, 0, 5, 0, 10);
    expect_pos(s, 1, 1, 5, 1, 10, 1e-4); // turned 90 degrees about z (normalized SHORT quaternion)
    expect_pos(s, 1, 2, 4, 0, 10, 1e-4);
    expect_pos(s, 2, 1, 12, 0, 10); // scaled by 2
    expect_pos(s, 2, 2, 10, 2, 10);
    expect_error("gpu_instancing_counts.gltf", "EXT_mesh_gpu_instancing attributes have different counts (3 and 2)");
}

TEST(GltfContainers, GlbExternalAndEmbeddedBuffersAgree) {
    Scene glb = load_gltf(data("box.glb"));
    Scene ext = load_gltf(data("external.gltf"));
    Scene emb = load_gltf(data("embedded.gltf"));
    for (const Scene* s : {&glb, &ext, &emb}) {
        SCOPED_TRACE(s->source);
        ASSERT_EQ(s->num_triangles(), 2u);
        expect_pos(*s, 0, 0, -1, 0.5, -1);
        expect_pos(*s, 0, 1, 1, 0.5, 1);
        expect_pos(*s, 0, 2, 1, 0.5, -1);
        expect_pos(*s, 1, 2, 1, 0.5, 1);
        expect_vec3(s->shading[1].n0, 0, 1, 0);
        ASSERT_EQ(s->materials.size(), 1u);
        EXPECT_FLOAT_EQ(s->materials[0].base_color[1], 0.5f);
    }
}

TEST(GltfNormals, MissingNormalsAreFlatAndCountedOncePerMesh) {
    Scene s = load_gltf(data("no_normals.gltf"));
    ASSERT_EQ(s.num_triangles(), 2u);
    EXPECT_EQ(s.meshes_without_normals, 1u); // one mesh, two instances
    // (1,0,0) x (0,0,-1) = (0,1,0)
    for (size_t t = 0; t < 2; ++t) {
        expect_vec3(s.shading[t].n0, 0, 1, 0);
        expect_vec3(s.shading[t].n2, 0, 1, 0);
    }
    expect_pos(s, 1, 2, 0, 1, -1);
}

TEST(GltfDegenerate, ZeroAreaAndNonFiniteTrianglesAreSkippedAndCounted) {
    Scene s = load_gltf(data("degenerate.gltf"));
    EXPECT_EQ(s.degenerate_triangles_skipped, 4u);
    ASSERT_EQ(s.num_triangles(), 2u);
    expect_pos(s, 0, 1, 1, 0, 0);
    expect_pos(s, 1, 0, 0, 0, 2);
    ASSERT_EQ(s.positions.size(), 6u);
}

TEST(GltfDegenerate, NanNormalMakesTheWholeTriangleFlat) {
    Scene s = load_gltf(data("degenerate.gltf"));
    ASSERT_EQ(s.num_triangles(), 2u);
    // The file's normals are (0,.71,.71), NaN, (0,.71,.71); the flat normal is +z.
    expect_vec3(s.shading[1].n0, 0, 0, 1);
    expect_vec3(s.shading[1].n1, 0, 0, 1);
    expect_vec3(s.shading[1].n2, 0, 0, 1);
}

TEST(GltfMirror, NegativeDeterminantKeepsWindingAndNormalsConsistent) {
    Scene s = load_gltf(data("mirror.gltf"));
    ASSERT_EQ(s.num_triangles(), 2u);
    for (size_t t = 0; t < 2; ++t) {
        SCOPED_TRACE("triangle " + std::to_string(t));
        std::array<double, 3> g = winding_normal(s, t);
        expect_vec3(s.shading[t].n0, 0, 0, 1); // x -> -x leaves a +z normal +z
        EXPECT_NEAR(g[2], 1.0, 1e-6);          // and the front face agrees
    }
    // (0,0,0), (1,0,0), (0,1,0) mirrored and re-wound: (0,0,0), (0,1,0), (-1,0,0).
    expect_pos(s, 0, 1, 0, 1, 0);
    expect_pos(s, 0, 2, -1, 0, 0);
}

// ---- materials and textures ---------------------------------------------------------------------

TEST(GltfMaterials, ParametersAreKeptAsTheFileSays) {
    Scene s = load_gltf(data("materials.gltf"));
    ASSERT_EQ(s.materials.size(), 10u); // 9 in the file + the default
    // glTF's parameters reach the device as they are: kernels/bsdf.cl is the model they define.
    const float metallic[10] = {0, 0, 0, 1, 0.4f, 0, 1, 0, 0, 1};
    const float transmission[10] = {0, 0, 1, 0, 0, 0, 0, 0.5f, 0, 0};
    for (size_t i = 0; i < 10; ++i) {
        EXPECT_FLOAT_EQ(s.materials[i].metallic, metallic[i]) << "material " << i;
        EXPECT_FLOAT_EQ(s.materials[i].transmission, transmission[i]) << "material " << i;
    }
    ASSERT_EQ(s.num_triangles(), 10u);
    for (uint32_t t = 0; t < 10; ++t) EXPECT_EQ(s.shading[t].material, t);
    expect_vec3(s.materials[0].base_color, 0.5, 0.25, 0.125);
    EXPECT_FLOAT_EQ(s.materials[0].roughness, 0.7f);
    EXPECT_FLOAT_EQ(s.materials[4].metallic, 0.4f);
    EXPECT_EQ(s.materials[5].flags, MATERIAL_FLAG_DOUBLE_SIDED);
    EXPECT_EQ(s.materials[0].flags, 0u);
    EXPECT_EQ(s.materials[0].base_color_tex, -1);
}

TEST(GltfMaterials, EmissionIsFactorTimesStrength) {
    Scene s = load_gltf(data("materials.gltf"));
    expect_vec3(s.materials[1].emission, 8, 4, 2);
    expect_vec3(s.materials[0].emission, 0, 0, 0);
}

TEST(GltfMaterials, TransmissionAndIor) {
    Scene s = load_gltf(data("materials.gltf"));
    EXPECT_FLOAT_EQ(s.materials[2].transmission, 1.f);
    EXPECT_FLOAT_EQ(s.materials[2].ior, 1.33f);
    EXPECT_FLOAT_EQ(s.materials[2].roughness, 0.3f);
    EXPECT_FLOAT_EQ(s.materials[7].transmission, 0.5f);
    EXPECT_FLOAT_EQ(s.materials[7].ior, 1.5f); // KHR_materials_ior default
    EXPECT_FLOAT_EQ(s.materials[3].metallic, 1.f);
    EXPECT_FLOAT_EQ(s.materials[3].roughness, 0.f);
}

TEST(GltfMaterials, SpecularExtensionScalesTheLayerAndDefaultsToOne) {
    Scene s = load_gltf(data("materials.gltf"));
    const dev::Material& m = s.materials[8];
    expect_vec3(m.specular_color, 1, 0.5, 0.25);
    EXPECT_FLOAT_EQ(m.specular_color[3], 0.5f);
    // Without the extension: specularFactor 1, specularColorFactor 1 (KHR_materials_specular).
    expect_vec3(s.materials[0].specular_color, 1, 1, 1);
    EXPECT_FLOAT_EQ(s.materials[0].specular_color[3], 1.f);
    EXPECT_FLOAT_EQ(s.materials[9].specular_color[3], 1.f);
    EXPECT_TRUE(s.warnings.empty()) << ::testing::PrintToString(s.warnings);
}

TEST(GltfMaterials, DefaultMaterialFollowsTheSpecification) {
    Scene s = load_gltf(data("materials.gltf"));
    // glTF 2.0: base colour 1, metallic 1, roughness 1 -> a rough white GGX metal by our mapping.
    const dev::Material& d = s.materials[9];
    expect_vec3(d.base_color, 1, 1, 1);
    EXPECT_FLOAT_EQ(d.metallic, 1.f);
    EXPECT_FLOAT_EQ(d.roughness, 1.f);
    EXPECT_EQ(d.base_color_tex, -1);
    // A material without pbrMetallicRoughness takes the same defaults.
    EXPECT_FLOAT_EQ(s.materials[6].metallic, 1.f);
    expect_vec3(s.materials[6].base_color, 1, 1, 1);
}

TEST(GltfTextures, SrgbTexelsDecodeToLinearWithSamplerBits) {
    Scene s = load_gltf(data("texture.gltf"));
    ASSERT_EQ(s.textures.size(), 2u);
    ASSERT_EQ(s.texels.size(), 8u);
    EXPECT_EQ(s.materials[0].base_color_tex, 0);
    EXPECT_EQ(s.materials[3].base_color_tex, 1);
    const dev::Texture& a = s.textures[0];
    EXPECT_EQ(a.offset, 0u);
    EXPECT_EQ(a.width, 2u);
    EXPECT_EQ(a.height, 2u);
    EXPECT_EQ(a.wrap, 1u); // CLAMP_TO_EDGE on s only
    EXPECT_EQ(s.textures[1].offset, 4u);
    EXPECT_EQ(s.textures[1].wrap, 3u | TEXTURE_NEAREST); // clamp s and t, magFilter NEAREST; from a bufferView
    // Top row first: (0,0,0,255) (255,255,255,255) / (128,64,188,255) (10,200,30,128).
    const std::array<float, 4> want[4] = {
        {0, 0, 0, 1}, {1, 1, 1, 1}, {srgb(128), srgb(64), srgb(188), 1}, {srgb(10), srgb(200), srgb(30), 128 / 255.f}};
    for (size_t t = 0; t < 8; ++t)
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(s.texels[t][size_t(c)], want[t % 4][size_t(c)], 1e-6) << t << c;
    EXPECT_NEAR(s.texels[2][0], 0.2158605, 1e-6); // sRGB 128
    EXPECT_FLOAT_EQ(s.shading[0].uv2[1], 1.f);
}

// The extension's example: u' = (0.5 v, 1 - 0.5 u) maps the unit square onto the lower left
// quadrant turned clockwise; a texCoord in the extension moves the reference to TEXCOORD_1; the
// two references share their texels.
TEST(GltfTextures, TextureTransformTexcoord1AndMirroredRepeat) {
    Scene s = load_gltf(data("texture_transform.gltf"));
    ASSERT_EQ(s.textures.size(), 2u);
    EXPECT_EQ(s.texels.size(), 4u);
    const dev::Texture& a = s.textures[size_t(s.materials[0].base_color_tex)];
    const float want[6] = {0, 0.5f, 0, -0.5f, 0, 1};
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(a.xform[k], want[k], 1e-6) << k; // pi / 2 to 6 digits
    EXPECT_EQ(a.texcoord, 0u);
    EXPECT_EQ(a.wrap, uint32_t(TEXTURE_MIRROR_S));
    const dev::Texture& b = s.textures[size_t(s.materials[1].base_color_tex)];
    EXPECT_EQ(b.texcoord, 1u);
    EXPECT_EQ(b.offset, a.offset);
    EXPECT_FLOAT_EQ(b.xform[2], 0.25f);
    ASSERT_EQ(s.uv1.size(), 6u);
    EXPECT_FLOAT_EQ(s.uv1[1][0], 3.f);
    EXPECT_FLOAT_EQ(s.uv1[2][1], 1.f);
    EXPECT_TRUE(s.warnings.empty()) << ::testing::PrintToString(s.warnings);
}

TEST(GltfTextures, OtherTexCoordSetsAndUndecodableImagesWarn) {
    Scene s = load_gltf(data("texture.gltf"));
    EXPECT_EQ(s.materials[1].base_color_tex, -1);
    EXPECT_EQ(s.materials[2].base_color_tex, -1);
    EXPECT_TRUE(has_warning(s, "TEXCOORD_2")) << ::testing::PrintToString(s.warnings);
    EXPECT_TRUE(has_warning(s, "image 1 could not be decoded")) << ::testing::PrintToString(s.warnings);
}

// ---- lights and cameras -------------------------------------------------------------------------

TEST(GltfLights, PointSpotAndDirectional) {
    Scene s = load_gltf(data("lights.gltf"));
    ASSERT_EQ(s.punctual_lights.size(), 4u);
    const dev::Light& point = s.punctual_lights[0];
    EXPECT_EQ(point.type, LIGHT_POINT);
    expect_vec3(point.position, 1, 2, 3);
    expect_vec3(point.radiance, 10, 5, 2.5);
    EXPECT_NEAR(punctual_light_power(point, 0), 4 * kPi * 17.5 / 3, 1e-3);

    const dev::Light& spot = s.punctual_lights[1];
    EXPECT_EQ(spot.type, LIGHT_SPOT);
    expect_vec3(spot.position, 1, 5, 0); // under the parent's translation
    expect_vec3(spot.direction, 0, -1, 0);
    expect_vec3(spot.radiance, 20, 20, 20);
    EXPECT_NEAR(spot.cos_inner, std::cos(0.2), 1e-6);
    EXPECT_NEAR(spot.cos_outer, std::cos(0.4), 1e-6);
    // The glTF falloff integrated over the cone: 2 pi I ((1 - cos_inner) + (cos_inner - cos_outer) / 3).
    EXPECT_NEAR(punctual_light_power(spot, 0),
                2 * kPi * 20 * ((1 - std::cos(0.2)) + (std::cos(0.2) - std::cos(0.4)) / 3), 1e-3);

    const dev::Light& cone = s.punctual_lights[2];
    expect_vec3(cone.direction, 0, 0, -1);
    EXPECT_NEAR(cone.cos_inner, 1.0, 1e-6);
    EXPECT_NEAR(cone.cos_outer, std::cos(kPi / 4), 1e-6);

    const dev::Light& sun = s.punctual_lights[3];
    EXPECT_EQ(sun.type, LIGHT_DIRECTIONAL);
    expect_vec3(sun.direction, -1, 0, 0); // -Z turned 90 degrees about +Y
    expect_vec3(sun.radiance, 3, 3, 3);
    EXPECT_NEAR(punctual_light_power(sun, 2.0), kPi * 4 * 3, 1e-4); // E over the disc of the scene's sphere
    EXPECT_TRUE(has_warning(s, "range is ignored"));
}

TEST(GltfCameras, CamerasInTraversalOrderWithExtras) {
    Scene s = load_gltf(data("cameras.gltf"));
    ASSERT_EQ(s.cameras.size(), 4u);
    const CameraDesc& side = s.cameras[0];
    EXPECT_EQ(side.name, "plain");
    expect_vec3(side.position, 0, 0, 0);
    expect_vec3(side.forward, -1, 0, 0);
    expect_vec3(side.up, 0, 1, 0);
    EXPECT_FLOAT_EQ(side.yfov, 0.8f);
    EXPECT_EQ(side.aspect, 0.f);                 // aspectRatio absent
    EXPECT_FLOAT_EQ(side.aperture_radius, 0.1f); // node extras
    EXPECT_FLOAT_EQ(side.focus_distance, 2.f);

    const CameraDesc& lens = s.cameras[1];
    EXPECT_EQ(lens.name, "with_extras");
    expect_vec3(lens.position, 0, 1, 5);
    expect_vec3(lens.forward, 0, 0, -1);
    EXPECT_FLOAT_EQ(lens.aspect, 1.5f);
    EXPECT_FLOAT_EQ(lens.aperture_radius, 0.05f); // camera extras
    EXPECT_FLOAT_EQ(lens.focus_distance, 4.f);

    const CameraDesc& sheared = s.cameras[2];
    expect_vec3(sheared.forward, 0, 0, -1);
    expect_vec3(sheared.up, 0, 1, 0); // (0,1,1) made orthogonal to forward
    EXPECT_FLOAT_EQ(sheared.aperture_radius, 0.f);
    EXPECT_FLOAT_EQ(sheared.znear, 0.01f);
    EXPECT_FALSE(sheared.orthographic);

    const CameraDesc& ortho = s.cameras[3];
    EXPECT_TRUE(ortho.orthographic);
    EXPECT_FLOAT_EQ(ortho.xmag, 1.f);
    EXPECT_FLOAT_EQ(ortho.ymag, 1.f);
    EXPECT_FLOAT_EQ(ortho.aspect, 1.f);
    EXPECT_FLOAT_EQ(ortho.znear, 0.1f);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
}

TEST(GltfCameras, NoCameraGivesAnEmptyList) {
    Scene s = load_gltf(data("index_types.gltf"));
    EXPECT_TRUE(s.cameras.empty());
    EXPECT_TRUE(s.punctual_lights.empty()); // no lights is the renderer's concern
}

// ---- errors -------------------------------------------------------------------------------------

// A file the loader refuses, and what its one line must say.
struct RefusedFile {
    const char* file; // in tests/data
    const char* says;
};

const RefusedFile kRefusedFiles[] = {
    {"does_not_exist.gltf", "cannot open file"},
    {"malformed.gltf", "malformed JSON"},
    {"not_gltf.gltf", "invalid glTF: \"asset\" object not found"},
    {"ext_required.gltf", "required extension 'EXT_meshopt_compression' is not supported"},
    {"accessor_range.gltf", "POSITION accessor 99 out of range"},
    {"index_range.gltf", "reference vertex 7 beyond the 3 vertices"},
    {"accessor_past_view.gltf", "accessor 0 reads past the end of bufferView 0"},
    {"view_past_buffer.gltf", "bufferView 0 extends past the end of buffer 0"},
    {"image_view_past_buffer.gltf", "bufferView 3 extends past the end of buffer 0"},
    {"huge_count.gltf", "accessor 0 count 3000000000 exceeds the limit of 2^31"},
    {"nonfinite_node.gltf", "node 0 ('overflow') has a non-finite transform"},
    {"cycle.gltf", "node graph cycle: node 0 ('a') is its own ancestor"},
    {"no_triangles.gltf", "no triangle geometry"},
    {"uri_parent.gltf", "buffer 0 URI '../outside.bin' points outside the scene directory"},
    {"uri_absolute.gltf", "URI '/etc/passwd' points outside the scene directory"},
    {"uri_sneaky.gltf", "points outside the scene directory"},
    {"uri_image_parent.gltf", "image 0 URI '..%2F..%2Fsecret.png' points outside"},
    {"missing_bin.gltf", "File not found : missing.bin"},
    {"nonfinite_material.gltf", "material 0 ('hot') has a non-finite baseColorFactor"},
    {"deep_json.gltf", "nested deeper than 64 levels"},
    {"truncated.glb", "invalid GLB"},
};

class GltfRefused : public ::testing::TestWithParam<RefusedFile> {};

TEST_P(GltfRefused, InOneLineNamingTheFile) { expect_error(GetParam().file, GetParam().says); }

INSTANTIATE_TEST_SUITE_P(GltfErrors, GltfRefused, ::testing::ValuesIn(kRefusedFiles),
                         [](const ::testing::TestParamInfo<RefusedFile>& refused) {
                             std::string name = refused.param.file; // the file's name, as a test name
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

TEST(GltfErrors, TextNamesTheDisplayNameAndRefusesFilesWithoutADirectory) {
    try {
        load_gltf_text("{\"asset\": ", "", "inline scene");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("inline scene: malformed JSON", 0), 0u) << e.what();
    }
    std::string text = read_text(data("external.gltf"));
    try {
        load_gltf_text(text, "", "inline scene");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("external.bin' names an external file"), std::string::npos) << e.what();
    }
    EXPECT_EQ(load_gltf_text(text, CLPPM_TEST_DATA, "inline scene").num_triangles(), 2u);
}

// ---- robustness ---------------------------------------------------------------------------------

// Deterministic mutations: digits changed or lengthened, bytes flipped, tails cut. Every result
// must be a Scene or a one-line clppm::Error, never a crash, hang or exception of another type.
std::string mutate(std::string s, uint64_t* state) {
    auto next = [state] {
        *state = *state * 6364136223846793005ull + 1442695040888963407ull;
        return uint32_t(*state >> 33);
    };
    switch (next() % 4) {
    case 0:
        for (int k = 0; k < 3; ++k) {
            size_t i = next() % s.size();
            while (i < s.size() && !std::isdigit((unsigned char)s[i])) ++i;
            if (i < s.size()) s[i] = char('0' + next() % 10);
        }
        break;
    case 1: {
        size_t i = next() % s.size();
        while (i < s.size() && !std::isdigit((unsigned char)s[i])) ++i;
        const char* big[] = {"99999", "0000000", "-1", "e9", ".5"};
        if (i < s.size()) s.insert(i, big[next() % 5]);
        break;
    }
    case 2:
        for (int k = 0; k < 4; ++k) s[next() % s.size()] ^= char(1u << (next() % 8));
        break;
    default: s.resize(next() % s.size()); break;
    }
    return s;
}

TEST(GltfRobustness, MutatedFilesLoadOrFailCleanly) {
    const char* files[] = {"hierarchy.gltf", "byte_stride.gltf", "texture.gltf", "lights.gltf",
                           "cameras.gltf",   "index_types.gltf", "box.glb"};
    std::string dir = test::make_temp_dir("gltf_fuzz");
    uint64_t state = 12345;
    int loaded = 0, failed = 0;
    for (const char* name : files) {
        std::string original = read_text(data(name));
        for (int i = 0; i < 300; ++i) {
            std::string mutated = mutate(original, &state);
            std::string path = dir + "/" + name;
            std::ofstream(path, std::ios::binary) << mutated;
            try {
                Scene s = load_gltf(path);
                ++loaded;
                EXPECT_EQ(s.positions.size(), 3 * s.shading.size());
                for (const dev::TriShading& t : s.shading) ASSERT_LT(t.material, s.materials.size());
            } catch (const Error& e) {
                ++failed;
                std::string msg = e.what();
                ASSERT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
                ASSERT_EQ(msg.find('\n'), std::string::npos) << msg;
            }
        }
    }
    std::filesystem::remove_all(dir);
    EXPECT_GT(loaded, 0);
    EXPECT_GT(failed, 0);
}

// ---- shipped scenes -----------------------------------------------------------------------------

bool has_glass(const Scene& s) {
    for (const dev::Material& m : s.materials)
        if (m.transmission > 0 && m.metallic < 1) return true;
    return false;
}

bool has_mirror(const Scene& s) {
    for (const dev::Material& m : s.materials)
        if (m.metallic == 1 && m.roughness == 0) return true;
    return false;
}

// Lambertian as the classic scenes mean it: no metal, no glass, no specular layer.
bool is_lambertian(const dev::Material& m) {
    return m.metallic == 0 && m.transmission == 0 && m.specular_color[3] == 0;
}

const dev::Material* emissive_material(const Scene& s) {
    for (const dev::Material& m : s.materials)
        if (m.emission[0] > 0 || m.emission[1] > 0 || m.emission[2] > 0) return &m;
    return nullptr;
}

TEST(GltfDefaultScene, IsTheEmbeddedCornellBox) {
    Scene s = load_default_scene();
    EXPECT_EQ(s.source, "<default scene>");
    EXPECT_EQ(s.num_triangles(), 5964u);
    const dev::Material* light = emissive_material(s);
    ASSERT_NE(light, nullptr);
    expect_vec3(light->emission, 16, 16, 16);
    ASSERT_EQ(s.cameras.size(), 1u);
    expect_vec3(s.cameras[0].position, 0, 0, 3.9);
    expect_vec3(s.cameras[0].forward, 0, 0, -1);
    EXPECT_FLOAT_EQ(s.cameras[0].yfov, 0.68f);
    EXPECT_TRUE(has_glass(s));
    EXPECT_TRUE(has_mirror(s));
    size_t lambertian = 0;
    for (const dev::Material& m : s.materials) lambertian += is_lambertian(m);
    EXPECT_EQ(lambertian, 4u); // the white, red and green walls and the light
    EXPECT_EQ(s.degenerate_triangles_skipped, 0u);
    EXPECT_TRUE(s.warnings.empty()) << ::testing::PrintToString(s.warnings);
    // The embedded copy is the shipped file.
    EXPECT_EQ(load_gltf(scene_file("cornell_box.gltf")).num_triangles(), s.num_triangles());
    EXPECT_LT(std::filesystem::file_size(scene_file("cornell_box.gltf")), 200u * 1024u);
}

TEST(GltfShippedScenes, AllLoadWithTheDocumentedContents) {
    struct Expect {
        const char* file;
        size_t triangles, lights;
    };
    for (const Expect& e :
         {Expect{"cornell_box.gltf", 5964, 0}, Expect{"caustic.gltf", 6020, 1}, Expect{"furnace.gltf", 960, 0},
          Expect{"plane_point_light.gltf", 2, 1}, Expect{"bunny_100k.gltf", 101772, 0}, Expect{"doorway.gltf", 34, 0},
          Expect{"dispersion_box.gltf", 2988, 0}}) {
        SCOPED_TRACE(e.file);
        Scene s = load_gltf(scene_file(e.file));
        EXPECT_EQ(s.num_triangles(), e.triangles);
        EXPECT_EQ(s.punctual_lights.size(), e.lights);
        EXPECT_EQ(s.cameras.size(), 1u);
        EXPECT_EQ(s.degenerate_triangles_skipped, 0u);
        EXPECT_EQ(s.meshes_without_normals, 0u);
        EXPECT_TRUE(s.warnings.empty()) << ::testing::PrintToString(s.warnings);
    }
    EXPECT_LT(std::filesystem::file_size(scene_file("bunny_100k.bin")), 8u << 20);
}

TEST(GltfShippedScenes, FurnaceIsAnInwardFacingEmitterOfAlbedoHalf) {
    Scene s = load_gltf(scene_file("furnace.gltf"));
    ASSERT_EQ(s.materials.size(), 1u);
    const dev::Material& m = s.materials[0];
    expect_vec3(m.base_color, 0.5, 0.5, 0.5);
    expect_vec3(m.emission, 1, 1, 1);
    EXPECT_TRUE(is_lambertian(m));
    EXPECT_EQ(m.flags, MATERIAL_FLAG_DOUBLE_SIDED);
    expect_vec3(s.cameras[0].position, 0, 0, 0);
    // Every normal points at the centre, where the camera is.
    for (size_t t = 0; t < s.num_triangles(); ++t) {
        const Vec3& p = s.positions[3 * t];
        const float* n = s.shading[t].n0;
        ASSERT_LT(p.x * n[0] + p.y * n[1] + p.z * n[2], 0.f) << t;
    }
}

TEST(GltfShippedScenes, PlaneUnderPointLight) {
    Scene s = load_gltf(scene_file("plane_point_light.gltf"));
    const dev::Light& l = s.punctual_lights.at(0);
    EXPECT_EQ(l.type, LIGHT_POINT);
    expect_vec3(l.position, 0, 1, 0);
    expect_vec3(l.radiance, 10, 10, 10);
    expect_vec3(s.materials.at(0).base_color, 0.5, 0.5, 0.5);
    expect_vec3(s.cameras.at(0).forward, 0, -1, 0);
    expect_vec3(s.cameras.at(0).up, 0, 0, -1);
    expect_vec3(s.shading.at(0).n0, 0, 1, 0);
}

TEST(GltfShippedScenes, CausticSpotAimsAtTheGlassSphere) {
    Scene s = load_gltf(scene_file("caustic.gltf"));
    const dev::Light& spot = s.punctual_lights.at(0);
    EXPECT_EQ(spot.type, LIGHT_SPOT);
    expect_vec3(spot.position, -3, 3.5, 0);
    double r = 1 / std::sqrt(2.0);
    expect_vec3(spot.direction, r, -r, 0);
    EXPECT_TRUE(has_glass(s));
}

// The corners of a one-triangle scene, within 1e-6.
void expect_corners(const Scene& s, const double (&want)[3][3]) {
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(s.positions[size_t(k)].x, want[k][0], 1e-6) << "corner " << k;
        EXPECT_NEAR(s.positions[size_t(k)].y, want[k][1], 1e-6) << "corner " << k;
        EXPECT_NEAR(s.positions[size_t(k)].z, want[k][2], 1e-6) << "corner " << k;
    }
}

// Skins (glTF 2.0 Sec. 3.7.3): each corner at the blend of its joints' matrices, the mesh node's
// own transform ignored (make_test_gltf.py skinned() gives the expected corners).
TEST(GltfSkin, SkinnedVerticesFollowTheirJoints) {
    Scene s = load_gltf(data("skinned.gltf"));
    ASSERT_EQ(s.num_triangles(), 1u);
    const double want[3][3] = {{0, 1, 0}, {1, 0, 0}, {0, 1.5, 0}};
    expect_corners(s, want);
    expect_vec3(s.shading[0].n0, 0, 0, 1); // translations leave the normals
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
}

// The pose a viewer opens a file in: the start of the first animation (make_test_gltf.py
// animated() gives the expected corners).
TEST(GltfAnimation, NodesStandAtTheFirstAnimationsStart) {
    Scene s = load_gltf(data("animated.gltf"));
    ASSERT_EQ(s.num_triangles(), 1u);
    const double want[3][3] = {{1, 2, 3}, {3, 2, 3}, {1, 4, 3}};
    expect_corners(s, want);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
    try {
        load_gltf(data("animated_bad.gltf"));
        FAIL() << "a VEC2 translation output loaded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("animation 0 channel 0: translation output must be a VEC3"),
                  std::string::npos)
            << e.what();
    }
}

// A sampler's outputs match its keyframe times: one each, three each for CUBICSPLINE (glTF 2.0,
// "Animation samplers"); a mismatch is a one-line error naming the file and the channel.
TEST(GltfAnimation, OutputsThatDoNotMatchTheTimesAreRefused) {
    const std::string dir = test::make_temp_dir("gltf_animation");
    const nlohmann::json file = nlohmann::json::parse(test::slurp(data("animated.gltf")));
    const struct {
        const char* what;
        int sampler, output; // animation 0's sampler, given this output accessor
        const char* message;
    } cases[] = {
        // Sampler 0 (LINEAR) reads 2 times from accessor 3; accessor 5 holds 6 translations.
        {"six values for two times", 0, 5,
         "animation 0 channel 0: 6 output values for 2 keyframe times (one per keyframe: 2)"},
        // Sampler 1 (CUBICSPLINE) with accessor 4's 2 values: one per key, not three.
        {"a cubic spline with one value per key", 1, 4,
         "animation 0 channel 1: 2 output values for 2 keyframe times (CUBICSPLINE needs 3 per keyframe: 6)"},
    };
    for (const auto& c : cases) {
        nlohmann::json broken = file;
        broken["animations"][0]["samplers"][size_t(c.sampler)]["output"] = c.output;
        const std::string path = dir + "/broken.gltf";
        std::ofstream(path) << broken.dump();
        try {
            load_gltf(path);
            ADD_FAILURE() << c.what << ": loaded";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << c.what << ": " << e.what();
            EXPECT_NE(std::string(e.what()).find("broken.gltf"), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
    }
}

} // namespace
} // namespace clppm
