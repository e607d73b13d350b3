// docs/video.md prints the ST 0601 tag table; it must name every tag of st0601_tags with the
// same name and JSON units, in tag order.
#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "klv/st0601.hpp"

TEST_CASE("docs/video.md tag table matches the ST 0601 declaration") {
    std::ifstream in(std::string(GIMBAL_SOURCE_DIR) + "/docs/video.md");
    REQUIRE(in);
    std::vector<std::vector<std::string>> rows;
    for (std::string line; std::getline(in, line);) {
        if (line.size() < 3 || line.compare(0, 2, "| ") != 0 || !std::isdigit(line[2])) continue;
        std::vector<std::string> cells;
        std::stringstream ss(line.substr(1));
        for (std::string cell; std::getline(ss, cell, '|');) {
            const auto first = cell.find_first_not_of(' ');
            const auto last = cell.find_last_not_of(' ');
            cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
        }
        rows.push_back(cells);
    }
    REQUIRE(rows.size() == gimbal::klv::st0601_tags.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const auto& spec = gimbal::klv::st0601_tags[i];
        INFO("docs row " << i + 1);
        REQUIRE(rows[i].size() >= 3);
        CHECK(rows[i][0] == std::to_string(spec.tag));
        CHECK(rows[i][1] == "`" + std::string(spec.name) + "`");
        CHECK(rows[i][2] == (spec.units.empty() ? std::string("-") : std::string(spec.units)));
    }
}
