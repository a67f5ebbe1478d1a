#include "scene/gltf/gltf_draco.h"

#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>

namespace clppm::gltf {

namespace {

const char* const kDraco = "KHR_draco_mesh_compression";

// The decoded primitive: one new buffer, appended to as views are added.
struct DecodedBuffer {
    tinygltf::Model& m;
    int buffer;

    // A tightly packed bufferView over `bytes`, 4-byte aligned.
    int add_view(const std::vector<unsigned char>& bytes) {
        std::vector<unsigned char>& data = m.buffers[size_t(buffer)].data;
        while (data.size() % 4) data.push_back(0);
        tinygltf::BufferView view;
        view.buffer = buffer;
        view.byteOffset = data.size();
        view.byteLength = bytes.size();
        data.insert(data.end(), bytes.begin(), bytes.end());
        m.bufferViews.push_back(view);
        return int(m.bufferViews.size() - 1);
    }

    int add_accessor(tinygltf::Accessor a, int view, size_t count) {
        a.bufferView = view;
        a.byteOffset = 0;
        a.count = count;
        a.sparse = tinygltf::Accessor().sparse; // the values are all here
        m.accessors.push_back(a);
        return int(m.accessors.size() - 1);
    }
};

template <typename T>
bool convert_all(const draco::Mesh& mesh, const draco::PointAttribute& att, int comps,
                 std::vector<unsigned char>* out) {
    out->resize(size_t(mesh.num_points()) * size_t(comps) * sizeof(T));
    T values[4] = {};
    for (draco::PointIndex i(0); i < mesh.num_points(); ++i) {
        if (!att.ConvertValue<T>(att.mapped_index(i), int8_t(comps), values)) return false;
        std::memcpy(out->data() + size_t(i.value()) * size_t(comps) * sizeof(T), values, size_t(comps) * sizeof(T));
    }
    return true;
}

bool convert(const draco::Mesh& mesh, const draco::PointAttribute& att, int component_type, int comps,
             std::vector<unsigned char>* out) {
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return convert_all<int8_t>(mesh, att, comps, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return convert_all<uint8_t>(mesh, att, comps, out);
    case TINYGLTF_COMPONENT_TYPE_SHORT: return convert_all<int16_t>(mesh, att, comps, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return convert_all<uint16_t>(mesh, att, comps, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return convert_all<uint32_t>(mesh, att, comps, out);
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return convert_all<float>(mesh, att, comps, out);
    default: return false;
    }
}

std::unique_ptr<draco::Mesh> decode(const tinygltf::Model& m, int view_index, const std::string& label,
                                    const LoadContext& ctx) {
    if (view_index < 0 || size_t(view_index) >= m.bufferViews.size())
        ctx.fail(label + " bufferView " + std::to_string(view_index) + " out of range");
    const tinygltf::BufferView& view = m.bufferViews[size_t(view_index)];
    if (view.buffer < 0 || size_t(view.buffer) >= m.buffers.size())
        ctx.fail(label + " bufferView " + std::to_string(view_index) + " has no valid buffer");
    const std::vector<unsigned char>& data = m.buffers[size_t(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
        ctx.fail(label + " bufferView " + std::to_string(view_index) + " extends past the end of its buffer");
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data.data() + view.byteOffset), view.byteLength);
    auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
    if (!type.ok()) ctx.fail(label + ": not Draco data (" + type.status().error_msg_string() + ")");
    if (type.value() != draco::TRIANGULAR_MESH) ctx.fail(label + ": the Draco data is a point cloud, not triangles");
    draco::Decoder decoder;
    auto mesh = decoder.DecodeMeshFromBuffer(&buffer);
    if (!mesh.ok()) ctx.fail(label + ": Draco data does not decode (" + mesh.status().error_msg_string() + ")");
    return std::move(mesh).value();
}

void decode_primitive(tinygltf::Model& m, tinygltf::Primitive& prim, const tinygltf::Value& ext,
                      const std::string& label, uint64_t* decoded_bytes, LoadContext& ctx) {
    if (!ext.IsObject() || !ext.Has("bufferView") || !ext.Get("bufferView").IsInt() || !ext.Has("attributes") ||
        !ext.Get("attributes").IsObject())
        ctx.fail(label + " needs a bufferView and an attributes object");
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP)
        ctx.fail(label + ": mode " + std::to_string(prim.mode) + " is not triangles");
    std::unique_ptr<draco::Mesh> mesh = decode(m, ext.Get("bufferView").GetNumberAsInt(), label, ctx);
    uint64_t bytes = uint64_t(mesh->num_faces()) * 12 + uint64_t(mesh->num_points()) * 64;
    *decoded_bytes += bytes;
    if (*decoded_bytes > kMaxExpandedAccessorBytes) ctx.fail(label + ": decoded meshes exceed 1 GiB");

    m.buffers.emplace_back();
    DecodedBuffer out{m, int(m.buffers.size() - 1)};
    // Indices: three per face, as UNSIGNED_INT whatever the file's accessor said.
    std::vector<unsigned char> idx(size_t(mesh->num_faces()) * 12);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
        for (int k = 0; k < 3; ++k) {
            uint32_t v = mesh->face(f)[k].value();
            std::memcpy(idx.data() + (size_t(f.value()) * 3 + size_t(k)) * 4, &v, 4);
        }
    tinygltf::Accessor index_accessor;
    index_accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    index_accessor.type = TINYGLTF_TYPE_SCALAR;
    prim.indices = out.add_accessor(index_accessor, out.add_view(idx), size_t(mesh->num_faces()) * 3);
    prim.mode = TINYGLTF_MODE_TRIANGLES; // the decoded faces are a triangle list

    const tinygltf::Value& attributes = ext.Get("attributes");
    for (const std::string& name : attributes.Keys()) {
        std::string what = label + " attribute " + name;
        const tinygltf::Value& id = attributes.Get(name);
        if (!id.IsInt()) ctx.fail(what + " is not a Draco attribute id");
        const draco::PointAttribute* att = mesh->GetAttributeByUniqueId(uint32_t(id.GetNumberAsInt()));
        if (!att) ctx.fail(what + ": no Draco attribute with id " + std::to_string(id.GetNumberAsInt()));
        auto in_prim = prim.attributes.find(name);
        if (in_prim == prim.attributes.end()) ctx.fail(what + " is not among the primitive's attributes");
        if (in_prim->second < 0 || size_t(in_prim->second) >= m.accessors.size())
            ctx.fail(what + " accessor " + std::to_string(in_prim->second) + " out of range");
        tinygltf::Accessor accessor = m.accessors[size_t(in_prim->second)];
        int comps = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
        if (comps < 1 || comps > 4 || comps != att->num_components())
            ctx.fail(what + " has " + std::to_string(att->num_components()) + " components where its accessor has " +
                     std::to_string(comps));
        std::vector<unsigned char> values;
        if (!convert(*mesh, *att, accessor.componentType, comps, &values))
            ctx.fail(what + " cannot be converted to its accessor's componentType");
        in_prim->second = out.add_accessor(accessor, out.add_view(values), size_t(mesh->num_points()));
    }
}

} // namespace

void decode_draco_primitives(tinygltf::Model& m, LoadContext& ctx) {
    uint64_t decoded_bytes = 0;
    for (size_t mi = 0; mi < m.meshes.size(); ++mi) {
        tinygltf::Mesh& mesh = m.meshes[mi];
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            tinygltf::Primitive& prim = mesh.primitives[p];
            auto ext = prim.extensions.find(kDraco);
            if (ext == prim.extensions.end()) continue;
            std::string label = labelled("mesh", int(mi), mesh.name) + " primitive " + std::to_string(p) + " " + kDraco;
            tinygltf::Value value = ext->second; // decode_primitive edits prim
            decode_primitive(m, prim, value, label, &decoded_bytes, ctx);
            prim.extensions.erase(kDraco);
        }
    }
}

} // namespace clppm::gltf
