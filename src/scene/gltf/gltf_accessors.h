// Reading glTF accessors safely: every element inside its buffer, strides within the glTF limit,
// normalised integers mapped as the specification says, sparse accessors (glTF 2.0 Sec. 3.6.2.3)
// and accessors without a bufferView (all zeros) expanded to a dense copy.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include <tiny_gltf.h>

#include "scene/gltf/gltf_context.h"

namespace clppm::gltf {

// A validated accessor: every element lies inside its buffer (or inside `owned`, the dense
// expansion of a sparse accessor).
struct AccessorView {
    const unsigned char* data = nullptr; // first element
    size_t stride = 0, count = 0;
    int component_type = 0, components = 0;
    bool normalized = false;
    std::shared_ptr<const std::vector<unsigned char>> owned; // keeps an expansion alive

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
        int comp_size = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
        int comps = tinygltf::GetNumComponentsInType(uint32_t(a.type));
        if (comp_size <= 0 || comps <= 0 || a.componentType == TINYGLTF_COMPONENT_TYPE_DOUBLE)
            ctx_.fail(label + " has an invalid componentType or type");
        size_t elem = size_t(comp_size) * size_t(comps);
        if (a.sparse.isSparse || a.bufferView < 0) return expanded(index, a, elem, comps, label);
        return view_without_sparse(a, elem, comps, label);
    }

private:
    // The first of `count` elements of `elem` bytes, `stride` apart, from `offset` in bufferView
    // `bv`; fails unless all lie inside it: offset + (count-1)*stride + elem <= byteLength, without
    // overflow.
    const unsigned char* bytes(const tinygltf::BufferView& bv, size_t offset, size_t count, size_t stride, size_t elem,
                               const std::string& label, int view_index) const {
        if (offset > bv.byteLength || (count && (count - 1) * stride + elem > bv.byteLength - offset))
            ctx_.fail(label + " reads past the end of bufferView " + std::to_string(view_index));
        return m_.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset + offset;
    }

    // The dense copy of a sparse accessor or one without a bufferView: the base elements (zeros
    // without a bufferView), then sparse.values written at sparse.indices. The indices must be
    // strictly increasing and below count (glTF 2.0 Sec. 3.6.2.3); values are tightly packed.
    AccessorView expanded(int index, const tinygltf::Accessor& a, size_t elem, int comps,
                          const std::string& label) const {
        auto cached = expanded_.find(index);
        if (cached == expanded_.end()) {
            uint64_t size = uint64_t(a.count) * elem;
            if (size > kMaxExpandedAccessorBytes || expanded_bytes_ + size > kMaxExpandedAccessorBytes)
                ctx_.fail(label + (a.sparse.isSparse ? " (sparse)" : " (without a bufferView)") +
                          " expands past the 1 GiB limit on expanded accessors");
            expanded_bytes_ += size;
            auto dense = std::make_shared<std::vector<unsigned char>>(size_t(size), 0);
            if (a.bufferView >= 0) {
                AccessorView base = view_without_sparse(a, elem, comps, label);
                for (size_t i = 0; i < a.count; ++i)
                    std::memcpy(dense->data() + i * elem, base.data + i * base.stride, elem);
            }
            if (a.sparse.isSparse) apply_sparse(a, elem, label, dense->data());
            cached = expanded_.emplace(index, std::move(dense)).first;
        }
        return AccessorView{cached->second->data(), elem,          a.count, a.componentType, comps,
                            a.normalized,           cached->second};
    }

    AccessorView view_without_sparse(const tinygltf::Accessor& a, size_t elem, int comps,
                                     const std::string& label) const {
        const tinygltf::BufferView& bv = buffer_view(a.bufferView, label);
        size_t stride = bv.byteStride ? bv.byteStride : elem;
        if (stride < elem || stride > kMaxByteStride)
            ctx_.fail("bufferView " + std::to_string(a.bufferView) + " byteStride " + std::to_string(bv.byteStride) +
                      " does not fit " + label);
        return AccessorView{bytes(bv, a.byteOffset, a.count, stride, elem, label, a.bufferView),
                            stride,
                            a.count,
                            a.componentType,
                            comps,
                            a.normalized,
                            nullptr};
    }

    void apply_sparse(const tinygltf::Accessor& a, size_t elem, const std::string& label, unsigned char* dense) const {
        const auto& sp = a.sparse;
        std::string sparse = label + " sparse";
        if (sp.count < 1 || uint64_t(sp.count) > uint64_t(a.count))
            ctx_.fail(sparse + " count " + std::to_string(sp.count) + " is not in 1.." + std::to_string(a.count));
        int isize = sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                    : sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                    : sp.indices.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                                         : 0;
        if (!isize) ctx_.fail(sparse + " indices must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
        if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0) ctx_.fail(sparse + " has a negative byteOffset");
        size_t n = size_t(sp.count);
        const unsigned char* idx =
            bytes(buffer_view(sp.indices.bufferView, sparse + " indices"), size_t(sp.indices.byteOffset), n,
                  size_t(isize), size_t(isize), sparse + " indices", sp.indices.bufferView);
        const unsigned char* val =
            bytes(buffer_view(sp.values.bufferView, sparse + " values"), size_t(sp.values.byteOffset), n, elem, elem,
                  sparse + " values", sp.values.bufferView);
        uint64_t previous = 0;
        for (size_t k = 0; k < n; ++k) {
            uint32_t i32 = 0;
            if (isize == 1) i32 = idx[k];
            else if (isize == 2) {
                uint16_t v;
                std::memcpy(&v, idx + 2 * k, 2);
                i32 = v;
            } else std::memcpy(&i32, idx + 4 * k, 4);
            uint64_t i = i32;
            if (i >= a.count)
                ctx_.fail(sparse + " index " + std::to_string(i) + " is beyond its " + std::to_string(a.count) +
                          " elements");
            if (k > 0 && i <= previous) ctx_.fail(sparse + " indices are not strictly increasing");
            previous = i;
            std::memcpy(dense + i * elem, val + k * elem, elem);
        }
    }

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
    mutable std::map<int, std::shared_ptr<const std::vector<unsigned char>>> expanded_;
    mutable uint64_t expanded_bytes_ = 0;
};

} // namespace clppm::gltf
