#pragma once
// The fixture of the tests every backend passes: one StoreBackend per test, chosen by the
// parameter. A backend that cannot run (no PostgreSQL server) fails the test, never skips it.

#include <gtest/gtest.h>

#include <string>

#include "tests/records/store_backend.h"

namespace vesica::app::testing {

class StoreTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { ASSERT_EQ(backend_.Unavailable(), "") << "backend " << GetParam() << " is unusable"; }

  StoreBackend backend_{GetParam()};
};

/// Names the parameterised tests ".../sqlite" and ".../postgres".
inline std::string BackendName(const ::testing::TestParamInfo<std::string>& info) { return info.param; }

}  // namespace vesica::app::testing
