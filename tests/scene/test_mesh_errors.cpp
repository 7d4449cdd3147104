// Every error the mesh loader reports: one MeshError whose message is the file
// name followed by the place (":LINE" or " ELEMENT N") and the problem. Each case
// checks the whole message, so a wrong line number or element index fails.
#include <catch2/catch.hpp>

#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "scene/mesh.hpp"
#include "support/mesh_test_files.hpp"

using mesh_test::Bytes;
using mesh_test::error_of;
using mesh_test::write_file;

namespace {

struct Case {
    const char* file;
    std::string content;
    std::string message; // what follows the file name
};

const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
const std::string ply_vertices = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                 "property float y\nproperty float z\n";
const std::string ply_faces = "element face 1\nproperty list uchar int vertex_indices\n";
const std::string ply_tri_header = ply_vertices + ply_faces + "end_header\n";
const std::string ply_tri_vertices = "0 0 0\n1 0 0\n0 1 0\n";

void check_cases(const std::vector<Case>& cases) {
    for (const Case& c : cases) {
        const auto path = write_file(c.file, c.content);
        INFO(c.file);
        CHECK(error_of(path) == path.string() + c.message);
    }
}

// A binary little-endian triangle: three float vertices (12 bytes each) and one
// face (1 + 3 * 4 bytes).
std::string binary_triangle(const std::string& count_type = "uchar", std::uint32_t count = 3) {
    Bytes b(false);
    const float v[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    for (const auto& p : v)
        b.put(p[0]).put(p[1]).put(p[2]);
    if (count_type == "uchar")
        b.put(static_cast<std::uint8_t>(count));
    else
        b.put(count);
    b.put(0).put(1).put(2);
    return "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
           "property float y\nproperty float z\nelement face 1\nproperty list " +
           count_type + " int vertex_indices\nend_header\n" + b.str();
}

} // namespace

TEST_CASE("mesh errors: missing file, directory and unknown format", "[mesh][errors]") {
    const auto missing = mesh_test::temp_dir() / "no-such-mesh.obj";
    CHECK(error_of(missing) ==
          missing.string() + ": cannot open mesh file: No such file or directory");
    const auto dir = mesh_test::temp_dir() / "folder.ply";
    std::filesystem::create_directories(dir);
    CHECK(error_of(dir) == dir.string() + ": cannot open mesh file: it is a directory");
    const auto stl = write_file("model.stl", "solid x\n");
    CHECK(error_of(stl) ==
          stl.string() + ": unknown mesh format '.stl' (expected .obj, .ply or .serialized)");
    const auto bare = write_file("model", "v 0 0 0\n");
    CHECK(error_of(bare) == bare.string() + ": unknown mesh format: the file name has no "
                                            "extension (expected .obj, .ply or .serialized)");
}

TEST_CASE("mesh errors: OBJ indices", "[mesh][errors][obj]") {
    check_cases({
        {"zero.obj", tri + "f 0 1 2\n",
         ":4: face vertex index 0 is invalid (OBJ indices start at 1)"},
        {"past_end.obj", tri + "f 1 2 3\nf 1 2 9\n",
         ":5: face vertex index 9 out of range (3 vertices)"},
        // A forward reference is fine while the file defines that vertex later.
        {"forward_then_short.obj", "v 0 0 0\nf 1 2 4\nv 1 0 0\nv 0 1 0\n",
         ":2: face vertex index 4 out of range (3 vertices)"},
        {"before_start.obj", tri + "f -4 1 2\n",
         ":4: face vertex index -4 reaches before the first vertex (3 defined so far)"},
        // Relative to the count at that line, not at the end of the file.
        {"before_start_later.obj", "v 0 0 0\nv 1 0 0\nf -3 -2 -1\nv 0 1 0\n",
         ":3: face vertex index -3 reaches before the first vertex (2 defined so far)"},
        {"normal_past_end.obj", tri + "vn 0 0 1\nf 1//1 2//1 3//2\n",
         ":5: face normal index 2 out of range (1 normals)"},
        {"normal_zero.obj", tri + "vn 0 0 1\nf 1//1 2//0 3//1\n",
         ":5: face normal index 0 is invalid (OBJ indices start at 1)"},
        {"texture_before_start.obj", tri + "vt 0 0\nf 1/-2 2/1 3/1\n",
         ":5: face texture index -2 reaches before the first texture (1 defined so far)"},
        {"not_a_number.obj", tri + "f 1 x 2\n", ":4: cannot read face corner 'x'"},
        {"too_many_slashes.obj", tri + "f 1/1/1/1 2 3\n", ":4: cannot read face corner '1/1/1/1'"},
        {"no_position.obj", tri + "f /1 2 3\n", ":4: cannot read face corner '/1'"},
    });
}

TEST_CASE("mesh errors: OBJ faces, coordinates and emptiness", "[mesh][errors][obj]") {
    check_cases({
        {"two_corners.obj", tri + "f 1 2\n", ":4: face has 2 vertices, needs at least 3"},
        {"no_corners.obj", tri + "f\n", ":4: face has 0 vertices, needs at least 3"},
        {"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
         ":2: vertex coordinate is not finite ('nan')"},
        {"inf.obj", "v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n",
         ":3: vertex coordinate is not finite ('-inf')"},
        {"overflow.obj", "v 0 0 1e999\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
         ":1: vertex coordinate is not finite ('1e999')"},
        {"two_coordinates.obj", "v 0 0\n", ":1: vertex needs three coordinates, got 2"},
        {"bad_coordinate.obj", "v 0 zero 0\n", ":1: cannot read vertex coordinate 'zero'"},
        {"normal_nan.obj", tri + "vn 0 nan 1\n", ":4: normal coordinate is not finite ('nan')"},
        {"normal_zero_length.obj", tri + "vn 0 0 0\n", ":4: normal has zero length"},
        {"no_faces.obj", tri, ": mesh has no faces"},
        {"empty.obj", "", ": mesh has no faces"},
        {"all_degenerate.obj", tri + "f 1 1 2\nv 2 0 0\nf 1 2 4\n",
         ": all 2 triangles are degenerate (zero area)"},
    });
}

TEST_CASE("mesh errors: PLY header", "[mesh][errors][ply]") {
    check_cases({
        {"not_ply.ply", "solid\n", ":1: not a PLY file (the first line is not 'ply')"},
        {"no_end.ply", "ply\nformat ascii 1.0\n", ": PLY header has no end_header line"},
        {"no_format.ply", "ply\nend_header\n", ":2: PLY header has no format line"},
        {"bad_format.ply", "ply\nformat binary_middle_endian 1.0\n",
         ":2: unknown PLY format 'binary_middle_endian'"},
        {"bad_type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\n",
         ":4: unknown PLY property type 'float128'"},
        {"bad_element.ply", "ply\nformat ascii 1.0\nelement vertex -3\n",
         ":3: expected 'element <name> <count>'"},
        {"orphan_property.ply", "ply\nformat ascii 1.0\nproperty float x\n",
         ":3: property before any element"},
        {"bad_keyword.ply", "ply\nformat ascii 1.0\nelephant 3\n",
         ":3: unknown PLY header line 'elephant 3'"},
        {"no_z.ply",
         "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
         "property float y\nend_header\n0 0\n",
         ":3: vertex element has no 'z' property"},
        {"some_normals.ply", ply_vertices + "property float nx\nend_header\n",
         ":3: vertex element has only some of nx, ny, nz"},
        {"twice.ply", ply_vertices + "property float x\nend_header\n",
         ":3: element 'vertex' has property 'x' twice"},
        {"float_indices.ply",
         ply_vertices + "element face 1\nproperty list uchar float "
                        "vertex_indices\nend_header\n",
         ":7: face property 'vertex_indices' must be a list of integers"},
        {"float_count.ply",
         ply_vertices + "element face 1\nproperty list float int "
                        "vertex_indices\nend_header\n",
         ":8: list length type must be an integer type"},
        {"no_index_list.ply",
         ply_vertices + "element face 1\nproperty list uchar int "
                        "corners\nend_header\n",
         ":7: face element has no vertex_indices list"},
        {"no_vertex.ply", "ply\nformat ascii 1.0\nend_header\n",
         ": PLY header declares no vertex element"},
    });
}

TEST_CASE("mesh errors: PLY body", "[mesh][errors][ply]") {
    check_cases({
        {"index_past_end.ply", ply_tri_header + ply_tri_vertices + "3 0 1 3\n",
         ": face 0: vertex index 3 out of range (3 vertices)"},
        {"index_negative.ply", ply_tri_header + ply_tri_vertices + "3 0 -1 2\n",
         ": face 0: vertex index -1 out of range (3 vertices)"},
        {"two_corners.ply", ply_tri_header + ply_tri_vertices + "2 0 1\n",
         ": face 0: face has 2 vertices, needs at least 3"},
        {"nan.ply", ply_tri_header + "0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n",
         ": vertex 2: coordinate is not finite"},
        {"inf.ply", ply_tri_header + "0 0 0\ninf 0 0\n0 1 0\n3 0 1 2\n",
         ": vertex 1: coordinate is not finite"},
        {"bad_number.ply", ply_tri_header + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n",
         ": vertex 1: line 11: expected a number, got 'zero'"},
        {"float_index.ply", ply_tri_header + ply_tri_vertices + "3 0 1.5 2\n",
         ": face 0: line 13: expected an integer, got '1.5'"},
        {"ascii_truncated.ply", ply_tri_header + ply_tri_vertices + "3 0 1\n",
         ": face 0: file ends early (truncated?)"},
        // An ASCII body can hold a value its declared type cannot: named as
        // such, not as a truncated file.
        {"count_past_uchar.ply", ply_tri_header + ply_tri_vertices + "300 0 1 2\n",
         ": face 0: line 13: 300 does not fit the declared type uchar (0 to 255)"},
        {"index_past_int.ply", ply_tri_header + ply_tri_vertices + "3 0 1 3000000000\n",
         ": face 0: line 13: 3000000000 does not fit the declared type int (-2147483648 to "
         "2147483647)"},
        {"no_faces.ply",
         ply_vertices + "element face 0\nproperty list uchar int vertex_indices\nend_header\n" +
             ply_tri_vertices,
         ": mesh has no faces"},
        {"only_vertices.ply", ply_vertices + "end_header\n" + ply_tri_vertices,
         ": mesh has no faces"},
        {"strip_bad_index.ply",
         ply_vertices +
             "element tristrips 1\nproperty list int int vertex_indices\n"
             "end_header\n" +
             ply_tri_vertices + "5 0 1 2 -1 7\n",
         ": tristrips 0: vertex index 7 out of range (3 vertices)"},
        {"strip_negative.ply",
         ply_vertices +
             "element tristrips 1\nproperty list int int vertex_indices\n"
             "end_header\n" +
             ply_tri_vertices + "3 0 -2 1\n",
         ": tristrips 0: vertex index -2 out of range (3 vertices)"},
    });
}

TEST_CASE("mesh errors: truncated binary PLY names the element", "[mesh][errors][ply]") {
    const std::string whole = binary_triangle();
    const std::size_t body = whole.find("end_header\n") + 11;
    REQUIRE(whole.size() == body + 36 + 13);
    REQUIRE(wp::load_mesh(write_file("whole.ply", whole)).triangles.size() == 1);
    struct Cut {
        std::size_t keep; // bytes of body kept
        std::string where;
    };
    for (const Cut& c :
         {Cut{0, "vertex 0"}, Cut{11, "vertex 0"}, Cut{12, "vertex 1"}, Cut{30, "vertex 2"},
          Cut{36, "face 0"}, Cut{37, "face 0"}, Cut{48, "face 0"}}) {
        const auto path =
            write_file("cut" + std::to_string(c.keep) + ".ply", whole.substr(0, body + c.keep));
        INFO(c.keep);
        CHECK(error_of(path) == path.string() + ": " + c.where + ": file ends early (truncated?)");
    }
}

TEST_CASE("mesh errors: absurd counts are truncation, not allocation failures",
          "[mesh][errors][ply]") {
    // A header claiming four billion vertices over a 49-byte body: the face bytes
    // read as a fourth vertex, the fifth runs out.
    std::string huge = binary_triangle();
    huge.replace(huge.find("vertex 3"), 8, "vertex 4000000000");
    const auto a = write_file("huge_count.ply", huge);
    CHECK(error_of(a) == a.string() + ": vertex 4: file ends early (truncated?)");
    // A face whose list claims four billion corners.
    const auto b = write_file("huge_list.ply", binary_triangle("uint", 4000000000u));
    CHECK(error_of(b) == b.string() + ": face 0: file ends early (truncated?)");
}

TEST_CASE("mesh errors: NaN in a binary PLY", "[mesh][errors][ply]") {
    std::string bytes = binary_triangle();
    const std::size_t body = bytes.find("end_header\n") + 11;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(bytes.data() + body + 12 + 4, &nan, 4); // vertex 1, y (host order is LE)
    const auto path = write_file("nan_binary.ply", bytes);
    CHECK(error_of(path) == path.string() + ": vertex 1: coordinate is not finite");
}

TEST_CASE("mesh errors: mutated files give a mesh or a MeshError, nothing else", "[mesh][errors]") {
    // Random byte changes, insertions and cuts of valid files: whatever the result,
    // it must be a loaded mesh or one MeshError line, never another exception.
    struct Seed {
        const char* name;
        std::string bytes;
    };
    std::ifstream obj_file(mesh_test::data_dir() / "cube.obj", std::ios::binary);
    std::ifstream ply_file(mesh_test::data_dir() / "cube_ascii.ply", std::ios::binary);
    const std::vector<Seed> seeds{
        {"fuzz.obj", std::string(std::istreambuf_iterator<char>(obj_file), {})},
        {"fuzz.ply", std::string(std::istreambuf_iterator<char>(ply_file), {})},
        {"fuzz_binary.ply", binary_triangle()},
    };
    const char alphabet[] = "0123456789-+./ \nfvnxyz#e\xff";
    std::mt19937 rng(5);
    std::size_t loaded = 0, rejected = 0;
    for (const Seed& seed : seeds) {
        for (int trial = 0; trial < 400; ++trial) {
            std::string bytes = seed.bytes;
            const int edits = 1 + trial % 4;
            for (int e = 0; e < edits && !bytes.empty(); ++e) {
                const std::size_t at = rng() % bytes.size();
                const char c = alphabet[rng() % (sizeof alphabet - 1)];
                switch (rng() % 4) {
                case 0:
                    bytes[at] = c;
                    break;
                case 1:
                    bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(at), c);
                    break;
                case 2:
                    bytes.erase(at, 1);
                    break;
                default:
                    bytes.resize(at);
                }
            }
            const auto path = write_file(seed.name, bytes);
            try {
                (void)wp::load_mesh(path);
                ++loaded;
            } catch (const wp::MeshError& e) {
                const std::string what = e.what();
                CHECK(what.rfind(path.string(), 0) == 0);
                CHECK(what.find('\n') == std::string::npos);
                ++rejected;
            }
        }
    }
    // Both outcomes occur, so the loop exercised the error paths and the readers.
    CHECK(loaded > 50);
    CHECK(rejected > 50);
}
