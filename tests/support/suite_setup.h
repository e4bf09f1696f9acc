// A test suite's shared set-up (SetUpTestSuite) that throws makes GoogleTest report every test of the
// suite as skipped, and CTest counts skipped tests as passing: a fixture that could not bake would hide
// all the tests it holds (seen once: a bad option in SparseReference's set-up, four tests "passed").
// SuiteSetup keeps what went wrong, and each test's SetUp() fails with it.
#pragma once

#include <exception>
#include <string>

#include <gtest/gtest.h>

namespace cpgi::test {

class SuiteSetup {
 public:
  /// Runs the suite's set-up, keeping the message of anything it throws.
  template <class SetUp>
  void run(SetUp&& setUp) {
    error_.clear();
    try {
      setUp();
    } catch (const std::exception& e) {
      error_ = std::string("the suite's set-up failed: ") + e.what();
    } catch (...) {
      error_ = "the suite's set-up failed with a non-standard exception";
    }
  }
  /// For a fixture's SetUp(): fails the test when the suite's set-up did.
  void require() const { ASSERT_TRUE(error_.empty()) << error_; }

 private:
  std::string error_;
};

}  // namespace cpgi::test
