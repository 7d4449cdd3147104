// one_line (util/one_line.hpp): what error types do to quoted input. Checked on
// hand-picked cases and, for random bytes, against the fuzzers' own independent
// check of a clean message (fuzz/clean_error.hpp).
#include <catch2/catch.hpp>

#include <random>
#include <string>

#include "../../fuzz/clean_error.hpp"
#include "util/one_line.hpp"

using wp::one_line;

TEST_CASE("one_line keeps printable UTF-8 and replaces control and invalid bytes", "[one_line]") {
    CHECK(one_line("plain text, 1e30") == "plain text, 1e30");
    CHECK(one_line("caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80") ==
          "caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80");
    CHECK(one_line("a\nb\rc\td\x1b[31me\x7f") == "a?b?c?d?[31me?");
    CHECK(one_line(std::string("nul\0byte", 8)) == "nul?byte");
    CHECK(one_line("\xff\xfe") == "??");           // never UTF-8
    CHECK(one_line("\xC0\xAF") == "??");           // overlong '/'
    CHECK(one_line("\xED\xA0\x80") == "???");      // a surrogate, U+D800
    CHECK(one_line("\xF4\x90\x80\x80") == "????"); // beyond U+10FFFF
    CHECK(one_line("cut \xE2\x82") == "cut ??");   // truncated sequence
    CHECK(one_line("\x80 stray") == "? stray");    // continuation without a lead
}

TEST_CASE("one_line makes any bytes a clean message", "[one_line]") {
    std::mt19937 rng(20261201);
    std::uniform_int_distribution<int> length(1, 24);
    std::uniform_int_distribution<int> byte(0, 255);
    for (int trial = 0; trial < 20000; ++trial) {
        std::string s(static_cast<std::size_t>(length(rng)), '\0');
        for (char& c : s)
            c = static_cast<char>(byte(rng));
        const std::string cleaned = one_line(s);
        INFO(trial);
        CHECK(cleaned.size() == s.size()); // one '?' per byte replaced
        CHECK(wp::fuzz::message_problem(cleaned).empty());
        CHECK(one_line(cleaned) == cleaned); // clean text is left as it is
    }
}

TEST_CASE("excerpt cuts long quoted input, never inside a UTF-8 sequence", "[one_line]") {
    using wp::excerpt;
    CHECK(excerpt("short") == "short");
    CHECK(excerpt(std::string(80, 'a')) == std::string(80, 'a'));
    CHECK(excerpt(std::string(81, 'a')) == std::string(80, 'a') + "...");
    CHECK(excerpt(std::string(1 << 20, 'm')).size() == 83);
    // A euro sign (3 bytes) across the cut at 4 is left out whole.
    CHECK(excerpt("abc\xE2\x82\xAC"
                  "def",
                  4) == "abc...");
    CHECK(excerpt("abc\xE2\x82\xAC"
                  "def",
                  6) == "abc\xE2\x82\xAC...");
}
