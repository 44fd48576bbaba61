// Reports the first few mismatches of one kind in full and counts the rest,
// so that a kernel ignoring an option fails readably rather than with
// thousands of lines.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <sstream>
#include <string>
#include <utility>

namespace rrc_test {

class Mismatches {
public:
    explicit Mismatches(std::string what) : what_(std::move(what)) {}
    ~Mismatches() {
        if (count_ > 0) ADD_FAILURE() << count_ << " " << what_ << " mismatches, the first:" << first_.str();
    }
    Mismatches(const Mismatches&) = delete;
    Mismatches& operator=(const Mismatches&) = delete;
    // The stream for the message of one mismatch.
    std::ostream& add() {
        sink_.str("");
        return ++count_ <= 8 ? first_ << "\n  " : sink_;
    }

private:
    std::string what_;
    int64_t count_ = 0;
    std::ostringstream first_, sink_;
};

}  // namespace rrc_test
