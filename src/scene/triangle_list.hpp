// The scene's triangles, and how they are held on the host.
//
// A triangle is read as a whole `Triangle` (three vertices in double
// precision, its material, and its normals and texture coordinates where it
// has them: 208 bytes). A big mesh held that way costs 208 bytes a
// triangle whether it has normals or not (a 5 M-triangle PLY, 1.04 GB), so a
// mesh file's triangles are held as the file indexes them
// (`IndexedTriangles`: its vertices once, three indices a triangle) and a
// `Triangle` is made from them when it is read, with the same doubles as
// before (docs/meshes.md, "Host memory of a big mesh, indexed"). Shapes of a
// few triangles (quads, inline triangles, a rectangle) are held whole.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <iterator>
#include <memory>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace wp {

// One triangle; its front face is the side of cross(v1 - v0, v2 - v0).
struct Triangle {
    std::array<glm::dvec3, 3> v;
    std::uint32_t material = 0; // index into Scene::materials
    // Unit vertex normals for shading (from a mesh file), interpolated across
    // the triangle; without them the geometric normal shades. They shade only:
    // which side is the front is still the winding's.
    bool has_normals = false;
    std::array<glm::dvec3, 3> normals{};
    // Texture coordinates per vertex (a mesh file's, a quad's corners);
    // without them a texture sees the barycentrics (b1, b2), as in Mitsuba.
    bool has_uvs = false;
    std::array<glm::dvec2, 3> uvs{};
};

// A mesh's triangles as indices into its vertices, in world space (the
// loader has applied the shape's transform, winding and normal flips).
struct IndexedTriangles {
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> normals;                   // empty, or one per position
    std::vector<glm::dvec2> uvs;                       // empty, or one per position
    std::vector<std::array<std::uint32_t, 3>> corners; // per triangle: v0, v1, v2
    // Per triangle, an index into Scene::materials; empty: all `material`.
    std::vector<std::uint32_t> materials;
    std::uint32_t material = 0;

    // Triangle i, whole: what it was when the loaders stored it whole.
    Triangle triangle(std::size_t i) const;
};

// A list of triangles, some held whole and some indexed. It reads like a
// std::vector<Triangle> that hands out copies: operator[], front(), back()
// and its iterators give a Triangle by value (bind it to a const reference,
// or a copy), and a triangle is changed with set(). The copies are const, so
// that writing to one (`list[i].v[0] = p`, a loop over `list[i].v` by
// non-const reference) does not compile rather than change nothing. A
// pointer to such a copy dangles once the statement or loop iteration ends:
// keep triangles by value.
class TriangleList {
  public:
    class const_iterator {
      public:
        using iterator_category = std::input_iterator_tag;
        using value_type = Triangle;
        using difference_type = std::ptrdiff_t;
        using pointer = void;
        using reference = const Triangle;

        const_iterator() = default;
        const Triangle operator*() const;
        const_iterator& operator++();
        const_iterator operator++(int) {
            const_iterator before = *this;
            ++*this;
            return before;
        }
        bool operator==(const const_iterator& o) const {
            return block_ == o.block_ && index_ == o.index_;
        }
        bool operator!=(const const_iterator& o) const { return !(*this == o); }

      private:
        friend class TriangleList;
        const_iterator(const TriangleList* list, std::size_t block, std::size_t index)
            : list_(list), block_(block), index_(index) {}
        const TriangleList* list_ = nullptr;
        std::size_t block_ = 0; // blocks_[block_], or blocks_.size() at the end
        std::size_t index_ = 0; // within the block
    };

    TriangleList() = default;
    TriangleList(std::initializer_list<Triangle> triangles);
    TriangleList(const TriangleList&) = default;
    TriangleList& operator=(const TriangleList&) = default;
    // A list moved from is empty, as a std::vector is.
    TriangleList(TriangleList&& o) noexcept
        : blocks_(std::move(o.blocks_)), size_(std::exchange(o.size_, 0)) {
        o.blocks_.clear();
    }
    TriangleList& operator=(TriangleList&& o) noexcept {
        blocks_ = std::move(o.blocks_);
        size_ = std::exchange(o.size_, 0);
        o.blocks_.clear();
        return *this;
    }

    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    const Triangle operator[](std::size_t i) const;
    const Triangle front() const { return (*this)[0]; }
    const Triangle back() const { return (*this)[size_ - 1]; }
    const_iterator begin() const { return {this, 0, 0}; }
    const_iterator end() const { return {this, blocks_.size(), 0}; }

    void push_back(const Triangle& t);
    void pop_back();
    // Appends a mesh's triangles, held indexed (shared by the list's copies:
    // a copied scene does not copy its meshes).
    void append(IndexedTriangles mesh);
    // Replaces triangle i (an indexed mesh's triangles are then held whole:
    // for tests and small scenes, not for big meshes).
    void set(std::size_t i, const Triangle& t);
    void clear() { *this = TriangleList(); }

    // The bytes the list holds on the heap, the meshes it shares with its
    // copies counted whole: for tests.
    std::size_t heap_bytes() const;

  private:
    // A run of triangles: held whole (`whole`) or a mesh's (`mesh`).
    struct Block {
        std::size_t first = 0; // the list's index of its first triangle
        std::vector<Triangle> whole;
        std::shared_ptr<const IndexedTriangles> mesh;
        std::size_t size() const { return mesh ? mesh->corners.size() : whole.size(); }
        Triangle at(std::size_t i) const { return mesh ? mesh->triangle(i) : whole[i]; }
    };
    // The block that holds triangle i.
    std::size_t block_of(std::size_t i) const;
    // The block's triangles held whole from now on.
    void hold_whole(Block& block);

    std::vector<Block> blocks_; // none empty
    std::size_t size_ = 0;
};

} // namespace wp
