// "Did you mean ...?": edit distances and when a name is near enough.
#include "util/suggest.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

TEST_CASE("edit_distance counts insertions, deletions and substitutions", "[suggest]") {
    CHECK(wp::edit_distance("", "") == 0);
    CHECK(wp::edit_distance("render", "render") == 0);
    CHECK(wp::edit_distance("rendr", "render") == 1);   // a deletion
    CHECK(wp::edit_distance("rennder", "render") == 1); // an insertion
    CHECK(wp::edit_distance("bemch", "bench") == 1);    // a substitution
    CHECK(wp::edit_distance("kitten", "sitting") == 3);
    CHECK(wp::edit_distance("", "info") == 4);
    CHECK(wp::edit_distance("abc", "cba") == wp::edit_distance("cba", "abc"));
}

TEST_CASE("nearest_name suggests only a near candidate", "[suggest]") {
    const std::vector<std::string> names = {"devices",  "render",  "bench",
                                            "converge", "compare", "info"};
    CHECK(wp::nearest_name("rendr", names) == "render");
    CHECK(wp::nearest_name("Render", names) == "render");
    CHECK(wp::nearest_name("converg", names) == "converge");
    CHECK(wp::nearest_name("compair", names) == "compare");
    CHECK(wp::nearest_name("inof", names) == "info");
    CHECK_FALSE(wp::nearest_name("xyzzy", names));
    CHECK_FALSE(wp::nearest_name("translate", names));
    CHECK_FALSE(wp::nearest_name("rendr", {}));
}
