// The renderer's scene: flat triangle arrays, materials, textures, lights and cameras, in world
// space, ready to be flattened into device buffers. Built by the glTF loader (gltf_load.cpp).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "shared_types.h"

namespace clppm {

struct Vec3 {
    float x = 0, y = 0, z = 0;
};

struct CameraDesc {
    std::string name;
    float position[3] = {0, 0, 0};
    float forward[3] = {0, 0, -1}; // unit
    float up[3] = {0, 1, 0};       // unit, orthogonal to forward
    float yfov = 0.8f;             // radians
    float aspect = 0.f;            // 0: unknown (glTF aspectRatio absent) -> take the image's
    float aperture_radius = 0.f;   // thin lens (extras), 0 = pinhole
    float focus_distance = 0.f;    // extras, 0 = unset
    float znear = 0.f;             // clipping distance along the view axis (glTF znear), 0 = none
    bool orthographic = false;     // glTF orthographic: parallel rays over 2 xmag x 2 ymag
    float xmag = 0.f, ymag = 0.f;  // its half extents (world units)
};

// The environment light (src/scene/environment.h sets it from the --env options).
struct Environment {
    bool present = false;
    std::array<float, 3> radiance{1.f, 1.f, 1.f}; // uniform radiance, or the factor on the map
    int32_t texture = -1;                         // the map in Scene::textures (linear); -1: uniform
    float rotation = 0.f;                         // radians about +Y (right-handed)
    bool hidden = false;                          // camera rays see black
    std::string source;                           // the file, "--env-color" or "the default environment"
};

// The world a file sets for itself: a scene-level extras.clppm_environment (docs/scenes.md,
// "Environment"). apply_environment uses it unless the command line sets the world.
struct FileWorld {
    enum class Kind { None, Color, Image };
    Kind kind = Kind::None;
    std::array<float, 3> color{};  // Kind::Color: uniform radiance (black allowed: no environment)
    std::string image;             // Kind::Image: the map's path, resolved against the file's folder
    double strength = 1.0;         // scales either
    double rotation_degrees = 0.0; // about +Y, as --env-rotate
};

// A homogeneous participating medium (kernels/medium.cl; docs/scenes.md, "Media").
struct MediumDesc {
    std::array<float, 3> density{};             // extinction sigma_t per scene unit, RGB
    std::array<float, 3> albedo{1.f, 1.f, 1.f}; // single-scattering albedo sigma_s / sigma_t, RGB
    float anisotropy = 0.f;                     // the Henyey-Greenstein g, in (-1, 1)
};

// The world's medium, filling space outside the closed volumes, the camera inside it: the
// command line's, else the file's own (src/scene/medium.h). present false: none.
struct WorldMedium {
    bool present = false;
    MediumDesc medium;
    std::string source; // "extras.clppm_medium" or the options that set it
};

struct Scene {
    // Triangles: three world-space positions each (p[3*i+k]), and shading attributes.
    std::vector<Vec3> positions;          // 3 per triangle
    std::vector<dev::TriShading> shading; // 1 per triangle (material index inside)
    // Normal mapping's tangent frames, 3 per triangle (one per corner) when some material has a
    // normalTexture, else empty: world-space tangent (xyz, zero where none could be made) and
    // the bitangent's sign w (glTF 2.0 Sec. 3.7.2.1: bitangent = cross(normal, tangent) w).
    std::vector<std::array<float, 4>> tangents;
    // COLOR_0, 3 per triangle (linear RGBA per corner) when some primitive has it, else empty;
    // (1, 1, 1, 1) for the corners of primitives without it. It multiplies the base colour.
    std::vector<std::array<float, 4>> colors;
    // TEXCOORD_1, 3 per triangle, when some texture reads it, else empty ((0, 0) for the corners
    // of primitives without it).
    std::vector<std::array<float, 2>> uv1;
    std::vector<dev::Material> materials;
    std::vector<std::string> material_names; // the file's names, for messages (may be shorter: unnamed)
    std::vector<dev::Texture> textures;
    std::vector<std::array<float, 4>> texels; // linear RGBA, all textures back to back
    // Punctual lights (KHR_lights_punctual); emissive triangles are found from materials by the
    // renderer, not listed here. type is LIGHT_POINT/SPOT/DIRECTIONAL; prim/area unused.
    std::vector<dev::Light> punctual_lights;
    std::vector<CameraDesc> cameras; // empty: no camera in the file
    Environment environment;
    FileWorld file_world;
    bool has_file_medium = false; // extras.clppm_medium (gltf_medium.h)
    MediumDesc file_medium;
    WorldMedium medium;                // set by apply_medium
    std::vector<std::string> variants; // KHR_materials_variants' names, in the file's order
    std::string variant;               // the one rendered; empty: the file's default materials
    // Diagnostics from loading, reported by the CLI.
    size_t degenerate_triangles_skipped = 0;
    size_t meshes_without_normals = 0;
    std::vector<std::string> warnings;
    std::string source;          // file name or "<default scene>"
    bool volumes_nested = false; // nest_volumes (volume_nesting.h) has set Material::outside

    size_t num_triangles() const { return shading.size(); }
};

} // namespace clppm
