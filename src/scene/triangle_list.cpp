#include "scene/triangle_list.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace wp {

Triangle IndexedTriangles::triangle(std::size_t i) const {
    const auto& [a, b, c] = corners[i];
    Triangle t{{positions[a], positions[b], positions[c]},
               materials.empty() ? material : materials[i]};
    if (!normals.empty()) {
        t.has_normals = true;
        t.normals = {normals[a], normals[b], normals[c]};
    }
    if (!uvs.empty()) {
        t.has_uvs = true;
        t.uvs = {uvs[a], uvs[b], uvs[c]};
    }
    return t;
}

const Triangle TriangleList::const_iterator::operator*() const {
    return list_->blocks_[block_].at(index_);
}

TriangleList::const_iterator& TriangleList::const_iterator::operator++() {
    if (++index_ == list_->blocks_[block_].size()) {
        ++block_;
        index_ = 0;
    }
    return *this;
}

TriangleList::TriangleList(std::initializer_list<Triangle> triangles) {
    for (const Triangle& t : triangles)
        push_back(t);
}

std::size_t TriangleList::block_of(std::size_t i) const {
    if (i >= size_)
        throw std::out_of_range("TriangleList: triangle " + std::to_string(i) + " of " +
                                std::to_string(size_));
    // The last block whose first triangle is at or before i.
    const auto after = std::upper_bound(blocks_.begin(), blocks_.end(), i,
                                        [](std::size_t k, const Block& b) { return k < b.first; });
    return static_cast<std::size_t>(after - blocks_.begin()) - 1;
}

const Triangle TriangleList::operator[](std::size_t i) const {
    const Block& block = blocks_[block_of(i)];
    return block.at(i - block.first);
}

void TriangleList::push_back(const Triangle& t) {
    if (blocks_.empty() || blocks_.back().mesh)
        blocks_.push_back(Block{size_, {}, nullptr});
    blocks_.back().whole.push_back(t);
    ++size_;
}

void TriangleList::pop_back() {
    Block& last = blocks_.back();
    hold_whole(last);
    last.whole.pop_back();
    if (last.whole.empty())
        blocks_.pop_back();
    --size_;
}

void TriangleList::append(IndexedTriangles mesh) {
    const std::size_t count = mesh.corners.size();
    if (count == 0)
        return;
    blocks_.push_back(Block{size_, {}, std::make_shared<const IndexedTriangles>(std::move(mesh))});
    size_ += count;
}

void TriangleList::set(std::size_t i, const Triangle& t) {
    Block& block = blocks_[block_of(i)];
    hold_whole(block);
    block.whole[i - block.first] = t;
}

void TriangleList::hold_whole(Block& block) {
    if (!block.mesh)
        return;
    block.whole.reserve(block.size());
    for (std::size_t i = 0; i < block.size(); ++i)
        block.whole.push_back(block.mesh->triangle(i));
    block.mesh.reset();
}

std::size_t TriangleList::heap_bytes() const {
    std::size_t bytes = blocks_.capacity() * sizeof(Block);
    for (const Block& b : blocks_) {
        bytes += b.whole.capacity() * sizeof(Triangle);
        if (const IndexedTriangles* m = b.mesh.get())
            bytes += m->positions.capacity() * sizeof(glm::dvec3) +
                     m->normals.capacity() * sizeof(glm::dvec3) +
                     m->uvs.capacity() * sizeof(glm::dvec2) +
                     m->corners.capacity() * sizeof(m->corners[0]) +
                     m->materials.capacity() * sizeof(std::uint32_t);
    }
    return bytes;
}

} // namespace wp
