#include <gtest/gtest.h>

#include "core/math/math.h"

TEST(Math, LuminanceOfWhiteIsOne) { EXPECT_NEAR(sst::luminance(sst::vec3(1.0f)), 1.0f, 1e-6f); }
