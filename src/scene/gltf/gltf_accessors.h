// Reading glTF accessors safely: every element inside its buffer, strides within the glTF limit,
// normalised integers mapped as the specification says.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include <tiny_gltf.h>

#include "scene/gltf/gltf_context.h"

namespace clppm::gltf {

// A validated accessor: every element lies inside its buffer.
struct AccessorView {
    const unsigned char* data = nullptr; // first element
    size_t stride = 0, count = 0;
    int component_type = 0, components = 0;
    bool normalized = false;

    // Component c of element i, normalised integers mapped as in glTF 2.0 Sec. 3.11.
    double get(size_t i, int c) const {
        const unsigned char* p = data + i * stride;
        switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return scalar<int8_t>(p, c, 127.0);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return scalar<uint8_t>(p, c, 255.0);
        case TINYGLTF_COMPONENT_TYPE_SHORT: return scalar<int16_t>(p, c, 32767.0);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return scalar<uint16_t>(p, c, 65535.0);
        case TINYGLTF_COMPONENT_TYPE_INT: return scalar<int32_t>(p, c, 2147483647.0);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return scalar<uint32_t>(p, c, 4294967295.0);
        default: return scalar<float>(p, c, 1.0);
        }
    }
    uint32_t index(size_t i) const { return uint32_t(get(i, 0)); }

private:
    template <typename T>
    double scalar(const unsigned char* p, int c, double max) const {
        T v;
        std::memcpy(&v, p + c * sizeof(T), sizeof(T));
        if (!normalized || std::is_floating_point<T>::value) return double(v);
        return std::max(double(v) / max, -1.0);
    }
};

class AccessorReader {
public:
    AccessorReader(const tinygltf::Model& m, const LoadContext& ctx) : m_(m), ctx_(ctx) {}

    AccessorView view(int index, const std::string& what) const {
        if (index < 0 || size_t(index) >= m_.accessors.size())
            ctx_.fail(what + " accessor " + std::to_string(index) + " out of range (" +
                      std::to_string(m_.accessors.size()) + " accessors)");
        const tinygltf::Accessor& a = m_.accessors[size_t(index)];
        std::string label = "accessor " + std::to_string(index);
        if (uint64_t(a.count) > kMaxAccessorCount)
            ctx_.fail(label + " count " + std::to_string(a.count) + " exceeds the limit of 2^31");
        if (a.sparse.isSparse) ctx_.fail(label + " is sparse; sparse accessors are not supported");
        int comp_size = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
        int comps = tinygltf::GetNumComponentsInType(uint32_t(a.type));
        if (comp_size <= 0 || comps <= 0 || a.componentType == TINYGLTF_COMPONENT_TYPE_DOUBLE)
            ctx_.fail(label + " has an invalid componentType or type");
        const tinygltf::BufferView& bv = buffer_view(a.bufferView, label);
        size_t elem = size_t(comp_size) * size_t(comps);
        size_t stride = bv.byteStride ? bv.byteStride : elem;
        if (stride < elem || stride > kMaxByteStride)
            ctx_.fail("bufferView " + std::to_string(a.bufferView) + " byteStride " + std::to_string(bv.byteStride) +
                      " does not fit " + label);
        // byteOffset + (count-1)*stride + elem <= byteLength, without overflow.
        if (a.byteOffset > bv.byteLength || (a.count && (a.count - 1) * stride + elem > bv.byteLength - a.byteOffset))
            ctx_.fail(label + " reads past the end of bufferView " + std::to_string(a.bufferView));
        const auto& buffer = m_.buffers[size_t(bv.buffer)].data;
        return AccessorView{
            buffer.data() + bv.byteOffset + a.byteOffset, stride, a.count, a.componentType, comps, a.normalized};
    }

private:
    const tinygltf::BufferView& buffer_view(int index, const std::string& owner) const {
        if (index < 0 || size_t(index) >= m_.bufferViews.size())
            ctx_.fail(owner + " has no valid bufferView (" + std::to_string(index) + ")");
        const tinygltf::BufferView& bv = m_.bufferViews[size_t(index)];
        std::string label = "bufferView " + std::to_string(index);
        if (bv.buffer < 0 || size_t(bv.buffer) >= m_.buffers.size())
            ctx_.fail(label + " buffer " + std::to_string(bv.buffer) + " out of range");
        size_t size = m_.buffers[size_t(bv.buffer)].data.size();
        if (bv.byteOffset > size || bv.byteLength > size - bv.byteOffset)
            ctx_.fail(label + " extends past the end of buffer " + std::to_string(bv.buffer));
        return bv;
    }

    const tinygltf::Model& m_;
    const LoadContext& ctx_;
};

} // namespace clppm::gltf
