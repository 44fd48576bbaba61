// Test support: a file of the source tree as text, for the tests that check
// the documentation and the headers against the code.  The build names the
// tree in RRC_SOURCE_DIR (tests/CMakeLists.txt).
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#ifndef RRC_SOURCE_DIR
#    error "RRC_SOURCE_DIR must name the source tree"
#endif

namespace rrc_test {

// The file at `relative` (to the source tree) as it is; a test failure where it cannot be read.
inline std::string read_source(const std::string& relative) {
    std::ifstream in(std::string(RRC_SOURCE_DIR) + "/" + relative, std::ios::binary);
    EXPECT_TRUE(in.good()) << "cannot read " << relative;
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace rrc_test
