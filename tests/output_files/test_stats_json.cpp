// The --stats writer (samples/vplkit/stats_json.hpp): what JSON cannot hold is written so the file
// still parses: NaN and infinity as null, control characters escaped, bytes that are not UTF-8
// replaced; the file appears whole or not at all.

#include "stats_json.hpp"
#include "test_files.hpp"

#include "vplkit/error.hpp"

#include <doctest/doctest.h>

#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace {

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace

TEST_CASE("a stats file with NaN, infinity and control characters parses back") {
    vplkit::test::ScratchFolder folder("stats-json");
    using vplkit::cli::json_number;
    const std::string awkward = std::string("scene \"a\"\\b\n\t\x01\x1f end", 19);
    nlohmann::ordered_json document = {{"nan", json_number(std::numeric_limits<double>::quiet_NaN())},
                                       {"inf", json_number(std::numeric_limits<double>::infinity())},
                                       {"minus_inf", json_number(-std::numeric_limits<double>::infinity())},
                                       {"finite", json_number(1.5)},
                                       {"awkward", awkward},
                                       {"not_utf8", std::string("path \xff\xfe.gltf")},
                                       // nlohmann's own float path: must not write "nan" either.
                                       {"raw_nan", std::numeric_limits<double>::quiet_NaN()}};
    const auto path = folder.path / "stats.json";
    vplkit::cli::write_json_file(path, document);
    CHECK(folder.names() == std::vector<std::string>{"stats.json"});

    const std::string text = read_text(path);
    for (char c : text) CHECK((static_cast<unsigned char>(c) >= 0x20 || c == '\n'));  // nothing raw below 0x20
    CHECK(text.find("\\u0001") != std::string::npos);
    for (const char* bare : {": nan", ": -nan", "NaN", ": inf", ": -inf", "Infinity"}) {
        CAPTURE(bare);
        CHECK(text.find(bare) == std::string::npos);
    }

    const nlohmann::json parsed = nlohmann::json::parse(text);  // strict: throws on invalid JSON
    CHECK(parsed["nan"].is_null());
    CHECK(parsed["inf"].is_null());
    CHECK(parsed["minus_inf"].is_null());
    CHECK(parsed["raw_nan"].is_null());
    CHECK(parsed["finite"].get<double>() == 1.5);
    CHECK(parsed["awkward"].get<std::string>() == awkward);
    CHECK(parsed["not_utf8"].get<std::string>() == "path \xEF\xBF\xBD\xEF\xBF\xBD.gltf");  // U+FFFD twice
}

TEST_CASE("a stats file into a missing folder fails naming it and writes nothing") {
    vplkit::test::ScratchFolder folder("stats-json-missing");
    const auto path = folder.path / "missing" / "stats.json";
    const std::string message = "could not write " + path.string();
    CHECK_THROWS_WITH_AS(vplkit::cli::write_json_file(path, {{"a", 1}}), doctest::Contains(message.c_str()),
                         vplkit::Error);
    CHECK(folder.names().empty());
}
